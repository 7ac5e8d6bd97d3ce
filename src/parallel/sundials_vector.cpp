#include "sphark/parallel/sundials_vector.hpp"

#include <nvector/nvector_serial.h>

#include "mpi_backend.hpp"

namespace sphark {

N_Vector make_vector_view(const Communicator& comm, std::size_t n, Real* data, SUNContext ctx) {
  if (const detail::MpiComm* mpi = comm.backend()) return detail::mpi_make_vector(*mpi, n, data, ctx);
  return N_VMake_Serial(static_cast<sunindextype>(n), data, ctx);
}

int create_sundials_context(const Communicator& comm, SUNContext* ctx) {
  return SUNContext_Create(const_cast<void*>(comm.mpi_handle()), ctx);
}

}  // namespace sphark
