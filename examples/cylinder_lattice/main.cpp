// Flow of a compressible liquid through a periodic lattice of cylinders (seed 004, §8): the
// medium-resolution comparison of the ghost maps (§8.1, Fig. 9) and the low-resolution ensemble
// (§8.2, eq. 37, Fig. 10). The scene lives in src/scenes/cylinder_lattice/; see README.md in this
// folder and docs/cylinder_lattice.md.
#include "sphark/scenes/cylinder_lattice/lattice_scene.hpp"

int main(int argc, char** argv) {
  sphark::CylinderLatticeScene scene;
  return sphark::run_scene_main(scene, argc, argv);
}
