#include "sphark/diagnostics/step_levels.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sphark {

StepLevels step_levels(const std::vector<Real>& dt) {
  StepLevels s;
  s.dt_min = std::numeric_limits<Real>::infinity();
  for (Real d : dt)
    if (std::isfinite(d)) s.dt_min = std::min(s.dt_min, d);
  for (Real d : dt) {
    if (!std::isfinite(d)) {
      ++s.unlimited;
      continue;
    }
    // the exact level: the largest k with 2^k dt_min <= d (ldexp is exact)
    int k = std::max(0, static_cast<int>(std::floor(std::log2(d / s.dt_min))));
    while (k > 0 && std::ldexp(s.dt_min, k) > d) --k;
    while (std::ldexp(s.dt_min, k + 1) <= d) ++k;
    if (s.count.size() <= static_cast<std::size_t>(k)) s.count.resize(static_cast<std::size_t>(k) + 1, 0);
    ++s.count[static_cast<std::size_t>(k)];
  }
  return s;
}

Real StepLevels::speedup() const {
  Real n = 0, work = 0;
  for (std::size_t k = 0; k < count.size(); ++k) {
    n += static_cast<Real>(count[k]);
    work += std::ldexp(static_cast<Real>(count[k]), -static_cast<int>(k));
  }
  return work > 0 ? n / work : 1;
}

}  // namespace sphark
