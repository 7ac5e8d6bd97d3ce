// Orszag-Tang vortex (seed 000, §IV-B, Figs. 2 and 3): SPMHD on the periodic unit square with
// five ways of controlling div B. The scene lives in src/scenes/orszag_tang/; see README.md.
// Under mpirun the run is distributed over the ranks (docs/scaling.md, "SPMHD").
#include "sphark/parallel/mpi_session.hpp"
#include "sphark/scenes/orszag_tang/orszag_tang_scene.hpp"

int main(int argc, char** argv) {
  sphark::OrszagTangScene scene;
  if (!sphark::MpiSession::launched_by_mpirun()) return sphark::run_scene_main(scene, argc, argv);
  sphark::MpiSession mpi(argc, argv);
  return mpi.run([&](const sphark::Communicator& world) { return sphark::run_scene_main(scene, argc, argv, world); });
}
