// Static cleaning test with a free boundary (seed 000, §IV-A, Fig. 1): a disc of 1976 fixed
// particles, only the cleaning subsystem. The scene lives in src/scenes/cleaning_disc/; see README.md.
// Under mpirun the runs are distributed over the ranks (docs/scaling.md).
#include "sphark/parallel/mpi_session.hpp"
#include "sphark/scenes/cleaning_disc/cleaning_disc_scene.hpp"

int main(int argc, char** argv) {
  sphark::CleaningDiscScene scene;
  if (!sphark::MpiSession::launched_by_mpirun()) return sphark::run_scene_main(scene, argc, argv);
  sphark::MpiSession mpi(argc, argv);
  return mpi.run([&](const sphark::Communicator& world) { return sphark::run_scene_main(scene, argc, argv, world); });
}
