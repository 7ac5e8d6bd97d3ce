#pragma once
// An axis-aligned box, periodic along the flagged axes (minimum-image convention).
#include <array>
#include <cmath>

#include "sphark/core/types.hpp"

namespace sphark {

// Round to the nearest integer (ties to even), equal to std::nearbyint in the default rounding
// mode for |x| < 2^51. Without SSE4.1 std::nearbyint is a libm call; this is two additions
// (x + 1.5 * 2^52 lies where the spacing of doubles is 1). Not folded away without -ffast-math.
inline Real round_to_nearest(Real x) {
  constexpr Real kShift = 6755399441055744.0;  // 1.5 * 2^52
  return (x + kShift) - kShift;
}

template <int D>
struct PeriodicBox {
  Vec<D> lo = Vec<D>::Zero();
  Vec<D> hi = Vec<D>::Ones();
  std::array<bool, D> periodic{};

  Vec<D> length() const { return hi - lo; }

  // Separation a - b reduced to the nearest periodic image.
  Vec<D> minimum_image(Vec<D> d) const {
    for (int k = 0; k < D; ++k) {
      if (!periodic[k]) continue;
      const Real L = hi[k] - lo[k];
      d[k] -= L * round_to_nearest(d[k] / L);
    }
    return d;
  }

  // Position mapped back into [lo, hi) along the periodic axes.
  Vec<D> wrap(Vec<D> x) const {
    for (int k = 0; k < D; ++k) {
      if (!periodic[k]) continue;
      const Real L = hi[k] - lo[k];
      x[k] -= L * std::floor((x[k] - lo[k]) / L);
      if (x[k] >= hi[k]) x[k] -= L;  // guards the round-off case x == hi
    }
    return x;
  }

  bool any_periodic() const {
    for (bool p : periodic)
      if (p) return true;
    return false;
  }
};

}  // namespace sphark
