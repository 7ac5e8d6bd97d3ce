// The oscillating elliptic water drop of seed 000, §IV-D: weakly compressible SPH with and
// without constrained velocity divergence cleaning, against the exact incompressible ellipse.
// The scene lives in src/scenes/water_drop/; see README.md in this folder. Under mpirun the
// runs are distributed over the ranks (docs/scaling.md).
#include "sphark/parallel/mpi_session.hpp"
#include "sphark/scenes/water_drop/drop_scene.hpp"

int main(int argc, char** argv) {
  sphark::WaterDropScene scene;
  if (!sphark::MpiSession::launched_by_mpirun()) return sphark::run_scene_main(scene, argc, argv);
  sphark::MpiSession mpi(argc, argv);
  return mpi.run([&](const sphark::Communicator& world) { return sphark::run_scene_main(scene, argc, argv, world); });
}
