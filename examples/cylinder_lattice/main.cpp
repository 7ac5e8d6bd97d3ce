// Flow of a compressible liquid through a periodic lattice of cylinders (seed 004, §8): the
// medium-resolution comparison of the ghost maps (§8.1, Fig. 9) and the low-resolution ensemble
// (§8.2, eq. 37, Fig. 10). The scene lives in src/scenes/cylinder_lattice/; see README.md in this
// folder and docs/cylinder_lattice.md.
// Under mpirun the single and medium cases are distributed over the ranks (docs/scaling.md).
#include "sphark/parallel/mpi_session.hpp"
#include "sphark/scenes/cylinder_lattice/lattice_scene.hpp"

int main(int argc, char** argv) {
  sphark::CylinderLatticeScene scene;
  if (!sphark::MpiSession::launched_by_mpirun()) return sphark::run_scene_main(scene, argc, argv);
  sphark::MpiSession mpi(argc, argv);
  return mpi.run([&](const sphark::Communicator& world) { return sphark::run_scene_main(scene, argc, argv, world); });
}
