#pragma once
// The MPI calls behind Communicator and MpiSession, implemented in mpi_backend.cpp (the only
// file that includes mpi.h; without SPHARK_HAVE_MPI they are never reached: a Communicator is
// then always serial). Private to src/parallel/ and src/integrate/.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <sundials/sundials_context.h>
#include <sundials/sundials_nvector.h>

#include "sphark/parallel/communicator.hpp"

namespace sphark::detail {

bool mpi_built();
bool mpi_initialized();
// MPI_Init_thread (funneled); returns false if MPI was already initialised (then not ours).
bool mpi_init(int& argc, char**& argv);
void mpi_finalize();
// A duplicate of MPI_COMM_WORLD.
std::shared_ptr<const MpiComm> mpi_world();

int mpi_rank(const MpiComm& c);
int mpi_size(const MpiComm& c);
const void* mpi_handle(const MpiComm& c);
void mpi_barrier(const MpiComm& c);
void mpi_allreduce(const MpiComm& c, double* values, std::size_t n, ReduceOp op);
void mpi_allreduce(const MpiComm& c, std::int64_t* values, std::size_t n, ReduceOp op);
void mpi_allgather(const MpiComm& c, const double* mine, std::size_t n, double* all);
void mpi_allgather(const MpiComm& c, const std::int64_t* mine, std::size_t n, std::int64_t* all);
void mpi_alltoall(const MpiComm& c, const std::int64_t* send, std::int64_t* received);
void mpi_exchange(const MpiComm& c, const std::vector<Communicator::Send>& sends,
                  const std::vector<Communicator::Receive>& receives);
[[noreturn]] void mpi_abort(const MpiComm& c, int code) noexcept;

// Reductions on the MPI_Comm that `comm` points at (N_VGetCommunicator of a parallel vector);
// no-ops when comm is nullptr.
void raw_allreduce(void* comm, double* values, std::size_t n, ReduceOp op);
void raw_allreduce(void* comm, std::int64_t* values, std::size_t n, ReduceOp op);
// Local length of a SUNDIALS parallel vector.
std::size_t parallel_local_length(N_Vector v);

// N_VMake_Parallel over `local` entries at `data` (not copied, not freed), global length the
// sum over the ranks of c (collective).
N_Vector mpi_make_vector(const MpiComm& c, std::size_t local, double* data, SUNContext ctx);

}  // namespace sphark::detail
