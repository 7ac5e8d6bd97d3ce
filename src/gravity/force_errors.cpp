#include "sphark/gravity/force_errors.hpp"

#include <algorithm>
#include <cmath>

namespace sphark {

std::vector<Real> relative_force_errors(const Real* test, const Real* ref, std::size_t n) {
  std::vector<Real> e(n);
  for (std::size_t i = 0; i < n; ++i) {
    Real d2 = 0, r2 = 0;
    for (std::size_t c = 3 * i; c < 3 * i + 3; ++c) {
      d2 += (test[c] - ref[c]) * (test[c] - ref[c]);
      r2 += ref[c] * ref[c];
    }
    e[i] = std::sqrt(d2 / r2);
  }
  return e;
}

Real quantile(std::vector<Real> v, Real p) {
  const auto k = static_cast<std::size_t>(std::lround(p * static_cast<Real>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace sphark
