#pragma once
// RAII around MPI itself: one MpiSession per program, first thing in main().
//
//   int main(int argc, char** argv) {
//     sphark::MpiSession mpi(argc, argv);
//     return mpi.run([&](const sphark::Communicator& world) { ...; return 0; });
//   }
//
// run() is the error policy of a distributed program: a CollectiveError (every rank agreed on
// the failure, see communicator.hpp) is printed once, by rank 0, and every rank returns the
// same exit code; any other exception escaping on some rank means the other ranks cannot be
// told (they may be waiting in a collective), so that rank prints "rank r of N: <what>" and
// MPI_Abort ends every rank with the exit code (the last resort; never a hang).
#include <functional>

#include "sphark/parallel/communicator.hpp"

namespace sphark {

class MpiSession {
 public:
  // MPI_Init_thread (MPI_THREAD_FUNNELED: OpenMP threads inside a rank, MPI from the main
  // thread) unless MPI is already initialised (then this session does not finalise it).
  // Built without MPI: nothing; world() is the serial Communicator.
  MpiSession(int& argc, char**& argv);
  ~MpiSession();  // frees the world duplicate, then MPI_Finalize (if this session initialised MPI)
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  static bool built_with_mpi();
  // True in a process started by an MPI launcher (mpirun / mpiexec: OMPI_COMM_WORLD_SIZE,
  // PMI_SIZE or PMIX_RANK set): a program that also runs alone creates a session only then.
  static bool launched_by_mpirun();
  const Communicator& world() const { return world_; }

  // body(world()) on every rank, with the error policy above; returns body's exit code, or
  // failure_code after a CollectiveError.
  int run(const std::function<int(const Communicator&)>& body, int failure_code = 1) const;

 private:
  bool owns_mpi_ = false;
  Communicator world_;
};

}  // namespace sphark
