#include "sphark/io/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace sphark {
namespace {

std::string seconds_text(double s) {
  char buf[48];
  if (s < 600) {
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  } else if (s < 36000) {
    std::snprintf(buf, sizeof buf, "%.0f min", s / 60);
  } else {
    std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  }
  return buf;
}

}  // namespace

ProgressReporter::ProgressReporter(Real t0, Real t_end, double min_interval_seconds)
    : ProgressReporter(t0, t_end, min_interval_seconds, std::cerr) {}

ProgressReporter::ProgressReporter(Real t0, Real t_end, double min_interval_seconds,
                                   std::ostream& out)
    : t0_(t0), t_end_(t_end), interval_(min_interval_seconds), out_(&out),
      start_(Clock::now()), last_(start_), t_last_(t0) {}

std::string ProgressReporter::format(Real t, long step, Real dt, double elapsed) const {
  const Real span = t_end_ - t0_;
  const Real fraction = span > 0 ? std::clamp((t - t0_) / span, Real(0), Real(1)) : Real(1);
  char buf[256];
  int n = std::snprintf(buf, sizeof buf, "t = %.3g / %.3g (%.0f%%)  step %ld  dt %.2g  elapsed %s",
                        t, t_end_, 100 * fraction, step, dt, seconds_text(elapsed).c_str());
  std::string line = (label_.empty() ? std::string() : label_ + ": ") + std::string(buf, static_cast<std::size_t>(n));
  if (fraction > 0 && fraction < 1) {
    line += "  ETA " + seconds_text(elapsed * (1 - fraction) / fraction);
  }
  return line;
}

bool ProgressReporter::update(Real t, long step, Real dt) {
  t_last_ = t;
  step_last_ = step;
  const auto now = Clock::now();
  if (std::chrono::duration<double>(now - last_).count() < interval_) return false;
  last_ = now;
  *out_ << format(t, step, dt, std::chrono::duration<double>(now - start_).count()) << '\n'
        << std::flush;
  return true;
}

void ProgressReporter::finish() {
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  char buf[160];
  std::snprintf(buf, sizeof buf, "done: t = %.6g  steps %ld  elapsed %s", t_last_, step_last_,
                seconds_text(elapsed).c_str());
  *out_ << (label_.empty() ? std::string() : label_ + ": ") << buf << '\n' << std::flush;
}

}  // namespace sphark
