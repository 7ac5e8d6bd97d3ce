// The magnetised molecular cloud core collapse (seed 000, §IV-C, Figs. 4-6): a rotating,
// magnetised 1 M_sun core collapses to a protostar (a sink) in a disc, with and without
// divergence cleaning. The scene lives in src/scenes/cloud_collapse/; see README.md here.
#include "sphark/scenes/cloud_collapse/cloud_collapse_scene.hpp"

int main(int argc, char** argv) {
  sphark::CloudCollapseScene scene;
  return sphark::run_scene_main(scene, argc, argv);
}
