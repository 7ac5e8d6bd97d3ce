// The oscillating elliptic water drop of seed 000, §IV-D: weakly compressible SPH with and
// without constrained velocity divergence cleaning, against the exact incompressible ellipse.
// The scene lives in src/scenes/water_drop/; see README.md in this folder.
#include "sphark/scenes/water_drop/drop_scene.hpp"

int main(int argc, char** argv) {
  sphark::WaterDropScene scene;
  return sphark::run_scene_main(scene, argc, argv);
}
