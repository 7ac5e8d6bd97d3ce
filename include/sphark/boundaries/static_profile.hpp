#pragma once
// Static node-density test of a ghost map (seed 004, §7): inner particles + their ghosts, node
// density (seed 004, eq. 3) of every inner and ghost particle, with the wall coordinate s.
#include <optional>
#include <vector>

#include "sphark/boundaries/ghosts.hpp"
#include "sphark/neighbours/periodic_box.hpp"

namespace sphark {

template <int D>
struct NodeDensityProfile {
  std::vector<Real> s_inner, n_inner;            // per inner particle
  std::vector<Real> s_ghost, n_ghost, x_ghost;   // per ghost (x: D each)
  std::size_t invalid = 0;                       // particles whose map left its valid range
};

// Ghosts of the inner particles x (D x n) with s > -layer_width, then n at every inner and ghost
// particle from the union inner + ghosts (Wendland C4, smoothing length h). `box` makes the
// evaluation periodic (e.g. along a cylinder's axis only); ghosts are not wrapped into it.
template <int D>
NodeDensityProfile<D> node_density_profile(const Wall<D>& wall, const std::vector<Real>& x, Real h,
                                           GhostMap map, Real layer_width,
                                           const std::optional<PeriodicBox<D>>& box = std::nullopt);

// Mean of n over the entries with lo < s <= hi (NaN-free: returns 0 and count 0 if empty).
struct BinMean {
  Real mean = 0;
  std::size_t count = 0;
};
BinMean mean_in_range(const std::vector<Real>& s, const std::vector<Real>& n, Real lo, Real hi);

}  // namespace sphark
