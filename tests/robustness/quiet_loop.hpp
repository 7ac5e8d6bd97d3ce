#pragma once
// A quiet time loop for the run-driver tests: one diagnostics column (t), a checkpoint at
// <dir>/checkpoint.bin every `checkpoint_every`, restarted from `restart` when given.
#include <filesystem>
#include <string>
#include <vector>

#include "sphark/run/time_loop.hpp"

namespace sphark::test {

inline TimeLoopSettings quiet_loop(const std::string& program, Real t_end, Real sample_every, Real checkpoint_every,
                                   const std::filesystem::path& dir, const Checkpoint* restart) {
  TimeLoopSettings s;
  s.program = program;
  s.t_end = t_end;
  s.sample_every = sample_every;
  s.diagnostics_csv = dir / "diagnostics.csv";
  s.columns = {"t"};
  s.checkpoint = dir / "checkpoint.bin";
  s.checkpoint_every = checkpoint_every;
  s.restart = restart;
  s.quiet = true;
  return s;
}

// Diagnostics rows of t alone.
inline TimeLoopHooks time_column() {
  TimeLoopHooks h;
  h.diagnostics = [](Real t, const Real*, const StepperStats&) { return std::vector<Real>{t}; };
  return h;
}

}  // namespace sphark::test
