// A self-gravitating gas sphere (issue #15): the cold uniform collapse against the exact free
// fall of every shell, and the Evrard collapse. The scene lives in src/scenes/gravitating_sphere/;
// see README.md in this folder.
#include "sphark/scenes/gravitating_sphere/gravitating_sphere_scene.hpp"

int main(int argc, char** argv) {
  sphark::GravitatingSphereScene scene;
  return sphark::run_scene_main(scene, argc, argv);
}
