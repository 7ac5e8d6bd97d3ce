// make_study_scene(): the scenes of examples/stepper_study by name, from the registry that the
// build generates (one register_<scene>_study_scenes per src/scenes/<scene>/study_scene.cpp).
#include <cmath>
#include <stdexcept>

#include "sphark/study/study_scene.hpp"

namespace sphark {

void register_all_study_scenes(StudySceneRegistry& r);  // generated: build/generated/study_registry.cpp

namespace {
const StudySceneRegistry& registry() {
  static const StudySceneRegistry r = [] {
    StudySceneRegistry all;
    register_all_study_scenes(all);
    return all;
  }();
  return r;
}
}  // namespace

std::vector<std::string> study_scene_names() {
  std::vector<std::string> names;
  for (const auto& e : registry()) names.push_back(e.name);
  return names;
}

std::unique_ptr<StudyScene> make_study_scene(const std::string& name, const StudySceneOptions& options) {
  if (options.spacing < 0 || !std::isfinite(options.spacing))
    throw std::invalid_argument("spacing=" + std::to_string(options.spacing) + ": must be positive");
  if (options.t_end < 0 || !std::isfinite(options.t_end))
    throw std::invalid_argument("t_end=" + std::to_string(options.t_end) + ": must be positive");
  std::string known;
  for (const auto& e : registry()) {
    if (e.name == name) return e.make(options);
    known += (known.empty() ? "" : ", ") + e.name;
  }
  throw std::invalid_argument("scene=" + name + ": unknown (known: " + known + ")");
}

}  // namespace sphark
