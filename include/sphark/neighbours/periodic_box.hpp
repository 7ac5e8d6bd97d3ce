#pragma once
// An axis-aligned box, periodic along the flagged axes (minimum-image convention).
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>

#include "sphark/core/types.hpp"
#include "sphark/simd/lanes.hpp"

namespace sphark {

// Round to the nearest integer (ties to even), equal to std::nearbyint in the default rounding
// mode for |x| < 2^51. Without SSE4.1 std::nearbyint is a libm call; this is two additions
// (x + 1.5 * 2^52 lies where the spacing of doubles is 1). Not folded away without -ffast-math.
// (For lanes of values too, simd/lanes.hpp.)
template <class S>
inline S round_to_nearest_lanes(S x) {
  constexpr Real kShift = 6755399441055744.0;  // 1.5 * 2^52
  return (x + kShift) - kShift;
}
inline Real round_to_nearest(Real x) { return round_to_nearest_lanes(x); }

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

  // n positions (D each, contiguous) wrapped into the box, into out[0 .. D n): for output, where
  // a state keeps the unwrapped trajectory.
  void wrap_all(const Real* x, std::size_t n, Real* out) const {
    for (std::size_t a = 0; a < n; ++a)
      Eigen::Map<Vec<D>>(out + D * a) = wrap(Eigen::Map<const Vec<D>>(x + D * a));
  }

  bool any_periodic() const {  // (parallel/halo: periodic images to send)
    for (bool p : periodic)
      if (p) return true;
    return false;
  }
};

// The minimum-image separation for hot pair loops: L and 1/L held by value (1/L = 0 on open
// axes, where nothing is subtracted). Equal to PeriodicBox::minimum_image except when d / L
// rounds differently from d * (1/L), i.e. for a pair exactly half a box apart.
template <int D>
struct MinimumImage {
  Vec<D> L = Vec<D>::Zero(), inv_L = Vec<D>::Zero();
  bool periodic = false;  // along some axis
  MinimumImage() = default;
  explicit MinimumImage(const std::optional<PeriodicBox<D>>& box) {
    if (!box) return;
    for (int k = 0; k < D; ++k)
      if (box->periodic[k]) {
        L[k] = box->hi[k] - box->lo[k];
        inv_L[k] = 1.0 / L[k];
        periodic = true;
      }
  }
  // x_a - x_b reduced to the nearest periodic image.
  Vec<D> operator()(const Real* xa, const Real* xb) const {
    Vec<D> d;
    for (int k = 0; k < D; ++k) {
      d[k] = xa[k] - xb[k];
      d[k] -= L[k] * round_to_nearest(d[k] * inv_L[k]);
    }
    return d;
  }
  // The same for lanes of separations x_a - x_b (simd/lanes.hpp); nothing without a periodic axis.
  template <class S>
  simd::LaneVec<S, D> operator()(simd::LaneVec<S, D> d) const {
    if (periodic)
      for (int k = 0; k < D; ++k) d[k] -= L[k] * round_to_nearest_lanes(d[k] * inv_L[k]);
    return d;
  }
};

}  // namespace sphark
