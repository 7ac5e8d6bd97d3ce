// make_study_scene(): the scenes of examples/stepper_study by name.
#include <cmath>
#include <stdexcept>

#include "sphark/scenes/cylinder_lattice_study.hpp"
#include "study_scene_factories.hpp"

namespace sphark {

std::vector<std::string> study_scene_names() { return {"drop", "disc", "disc_damped", "orszag_tang", "lattice"}; }

std::unique_ptr<StudyScene> make_study_scene(const std::string& name, const StudySceneOptions& options) {
  if (options.spacing < 0 || !std::isfinite(options.spacing))
    throw std::invalid_argument("spacing=" + std::to_string(options.spacing) + ": must be positive");
  if (options.t_end < 0 || !std::isfinite(options.t_end))
    throw std::invalid_argument("t_end=" + std::to_string(options.t_end) + ": must be positive");
  if (name == "drop") return detail::make_drop_study_scene(options);
  if (name == "disc") return detail::make_disc_study_scene(options, 0.0);
  if (name == "disc_damped") return detail::make_disc_study_scene(options, 0.3);
  if (name == "orszag_tang") return detail::make_orszag_tang_study_scene(options);
  if (name == "lattice") return make_lattice_study_scene(options);
  throw std::invalid_argument("scene=" + name + ": unknown (known: drop, disc, disc_damped, orszag_tang, lattice)");
}

}  // namespace sphark
