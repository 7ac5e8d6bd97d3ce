#pragma once
// Constructors of the stepper-study scenes (one file each under src/study/), used by
// make_study_scene() (src/study/study_scenes.cpp).
#include <memory>

#include "sphark/study/study_scene.hpp"

namespace sphark::detail {

std::unique_ptr<StudyScene> make_drop_study_scene(const StudySceneOptions& options);
// sigma = 0: the conservative cleaning subsystem ("disc"); sigma > 0: damped ("disc_damped").
std::unique_ptr<StudyScene> make_disc_study_scene(const StudySceneOptions& options, Real sigma);
std::unique_ptr<StudyScene> make_orszag_tang_study_scene(const StudySceneOptions& options);

}  // namespace sphark::detail
