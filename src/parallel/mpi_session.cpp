#include "sphark/parallel/mpi_session.hpp"

#include <cstdlib>

#include <cstdio>
#include <exception>

#include "mpi_backend.hpp"

namespace sphark {

MpiSession::MpiSession(int& argc, char**& argv) {
  if (!detail::mpi_built()) return;
  owns_mpi_ = detail::mpi_init(argc, argv);
  world_ = Communicator(detail::mpi_world());
}

MpiSession::~MpiSession() {
  world_ = Communicator();  // MPI_Comm_free of our duplicate (other copies free theirs if still possible)
  if (owns_mpi_) detail::mpi_finalize();
}

bool MpiSession::built_with_mpi() { return detail::mpi_built(); }

bool MpiSession::launched_by_mpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

int MpiSession::run(const std::function<int(const Communicator&)>& body, int failure_code) const {
  try {
    return body(world_);
  } catch (const CollectiveError& e) {  // every rank is here, with the same message
    if (world_.rank() == 0) std::fprintf(stderr, "error: %s\n", e.what());
    return failure_code;
  } catch (const std::exception& e) {
    world_.abort(failure_code, e.what());
  } catch (...) {
    world_.abort(failure_code, "unknown exception");
  }
}

}  // namespace sphark
