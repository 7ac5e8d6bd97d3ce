#pragma once
// Static node-density test of a ghost map (seed 004, §7): inner particles + their ghosts, node
// density (seed 004, eq. 3) of every inner and ghost particle, with the wall coordinate s.
#include <functional>
#include <optional>
#include <vector>

#include "sphark/boundaries/ghosts.hpp"
#include "sphark/boundaries/relaxation.hpp"
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

// A relaxed particle set inside a wall's fluid side, in two stages:
//  1. relax_uniform on n_box particles in the fully periodic relax_box (a uniform glass);
//  2. keep the particles with s < 0 and relax_near_wall with `relax_map` ghosts in the loop,
//     moving only the particles within band_H kernel radii of the wall for which `may_move`
//     is true (the rest is already uniform and only feeds n).
// wall_box: the physical periodic axes for stage 2 (e.g. the cylinder's axis), or nullopt.
template <int D>
struct RelaxedSet {
  std::vector<Real> x;  // inner particles, D each
  RelaxReport bulk, wall;
};
template <int D>
RelaxedSet<D> relaxed_set(const Wall<D>& wall, const PeriodicBox<D>& relax_box, std::size_t n_box,
                          GhostMap relax_map, const std::optional<PeriodicBox<D>>& wall_box,
                          const std::function<bool(const Vec<D>&)>& may_move, Real band_H = 3,
                          unsigned seed = 1, const RelaxOptions& opt = {});

// Mean of n over the entries with lo < s <= hi (NaN-free: returns 0 and count 0 if empty).
struct BinMean {
  Real mean = 0;
  std::size_t count = 0;
};
BinMean mean_in_range(const std::vector<Real>& s, const std::vector<Real>& n, Real lo, Real hi);

}  // namespace sphark
