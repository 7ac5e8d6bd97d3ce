// Static cleaning test with a free boundary (seed 000, §IV-A, Fig. 1): a disc of 1976 fixed
// particles, only the cleaning subsystem. The scene lives in src/scenes/cleaning_disc/; see README.md.
#include "sphark/scenes/cleaning_disc/cleaning_disc_scene.hpp"

int main(int argc, char** argv) {
  sphark::CleaningDiscScene scene;
  return sphark::run_scene_main(scene, argc, argv);
}
