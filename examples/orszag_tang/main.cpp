// Orszag-Tang vortex (seed 000, §IV-B, Figs. 2 and 3): SPMHD on the periodic unit square with
// five ways of controlling div B. The scene lives in src/scenes/orszag_tang/; see README.md.
#include "sphark/scenes/orszag_tang/orszag_tang_scene.hpp"

int main(int argc, char** argv) {
  sphark::OrszagTangScene scene;
  return sphark::run_scene_main(scene, argc, argv);
}
