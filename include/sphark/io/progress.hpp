#pragma once
// A progress line for long runs, printed at most every `min_interval_seconds` (wall clock):
//   t = 0.0312 / 0.1 (31%)  step 1234  dt 2.1e-06  elapsed 12 s  ETA 26 s
// The ETA extrapolates the wall time per unit of simulated time so far.
#include <chrono>
#include <iosfwd>
#include <string>

#include "sphark/core/types.hpp"

namespace sphark {

class ProgressReporter {
 public:
  // Lines go to `out` (default std::cerr).
  ProgressReporter(Real t0, Real t_end, double min_interval_seconds = 2);
  ProgressReporter(Real t0, Real t_end, double min_interval_seconds, std::ostream& out);

  // Prints a line if at least min_interval_seconds passed since the last line (or since
  // construction for the first line). Returns true if it printed.
  bool update(Real t, long step, Real dt);
  // Prints the final line unconditionally: "done: t = 0.1  steps 4000  elapsed 40 s".
  void finish();

  // Every line begins with "<label>: " (runs side by side: whose line it is); empty: no prefix.
  void set_label(std::string label) { label_ = std::move(label); }

  // The line update() would print for these values and `elapsed_seconds` of wall time.
  std::string format(Real t, long step, Real dt, double elapsed_seconds) const;

 private:
  using Clock = std::chrono::steady_clock;
  Real t0_, t_end_;
  double interval_;
  std::ostream* out_;
  Clock::time_point start_, last_;
  Real t_last_ = 0;
  long step_last_ = 0;
  std::string label_;
};

}  // namespace sphark
