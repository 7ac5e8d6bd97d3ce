#pragma once
// The cylinder lattice (seed 004, §8.2) as a stepper-study scene (study/study_scene.hpp).
#include <memory>

#include "sphark/study/study_scene.hpp"

namespace sphark {

// 100 particles (or fluid area / spacing^2), density-preserving ghosts, v0 = 0.5, t_end = 1,
// 10 output times; no exact solution (exact_error is NaN).
std::unique_ptr<StudyScene> make_lattice_study_scene(const StudySceneOptions& options);

}  // namespace sphark
