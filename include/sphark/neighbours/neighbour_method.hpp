#pragma once
// Which neighbour-list builder to use for a set of per-particle radii, and a search object that
// applies the rule at every build (both builders give identical lists).
//
// Predictor. The cell grid sizes its cells by the largest radius r_max, so particle i
// distance-tests the particles of 27 cells of volume r_max^3, about 27 (r_max / r_i)^3 times the
// particles inside its own radius; the kd-tree tests a bounded multiple of the pairs it lists.
// Their cost ratio therefore grows with
//   Q = mean_i (r_max / r_i)^3        (1 for equal radii)
// and the grid is chosen while Q stays below the measured crossover (bench/neighbours_wide_h,
// docs/collapse_parts.md, 1 thread, 1e5-8e5 particles): grid/tree time 0.72 at Q = 1, 0.79 at
// 1.12, 0.90 at 1.66, 1.34 at 3.5, 4.2 at 21 (the collapse's sphere in its box at t = 0),
// 17-19 at Q >= 200 (a collapsed core): log-linear interpolation puts the crossover at Q = 2.
// The ratio max r / median r does not predict it: 1.00 in all the scenes where the grid wins
// and in the first two where it loses (the ambient particles are the majority).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/neighbours/kd_tree_search.hpp"
#include "sphark/neighbours/neighbour_search.hpp"

namespace sphark {

enum class NeighbourMethod { cell_grid, kd_tree };

// Q = mean (r_max / r_i)^3 over the radii (capped at r_max, as the builders cap them); 1 without radii.
Real cell_grid_overhead(const Real* radii, std::size_t n, Real r_max);

inline constexpr Real kGridCrossover = 2.0;  // measured, see above

inline NeighbourMethod choose_neighbour_method(const Real* radii, std::size_t n, Real r_max,
                                               Real crossover = kGridCrossover) {
  return cell_grid_overhead(radii, n, r_max) < crossover ? NeighbourMethod::cell_grid : NeighbourMethod::kd_tree;
}

// NeighbourSearch's interface; each build picks the builder by the rule (without radii: the
// grid). The lists do not depend on the choice, so switching between builds is harmless.
template <int D>
class AdaptiveNeighbourSearch {
 public:
  explicit AdaptiveNeighbourSearch(std::optional<PeriodicBox<D>> box = std::nullopt, Real crossover = kGridCrossover)
      : grid_(box), tree_(box), crossover_(crossover) {}

  void build(const Real* x, std::size_t n, Real radius, const std::uint32_t* key = nullptr,
             const Real* radii = nullptr) {
    method_ = radii ? choose_neighbour_method(radii, n, radius, crossover_) : NeighbourMethod::cell_grid;
    if (method_ == NeighbourMethod::cell_grid)
      grid_.build(x, n, radius, key, radii);
    else
      tree_.build(x, n, radius, key, radii);
  }
  void renumber(const std::vector<std::uint32_t>& order) {
    if (method_ == NeighbourMethod::cell_grid)
      grid_.renumber(order);
    else
      tree_.renumber(order);
  }
  const std::vector<std::uint32_t>& cell_order() const { return grid() ? grid_.cell_order() : tree_.cell_order(); }
  void query(const Vec<D>& p, Real radius, std::vector<std::uint32_t>& out) const {
    if (grid())
      grid_.query(p, radius, out);
    else
      tree_.query(p, radius, out);
  }
  const NeighbourList& list() const { return grid() ? grid_.list() : tree_.list(); }
  Real radius() const { return grid() ? grid_.radius() : tree_.radius(); }
  const std::optional<PeriodicBox<D>>& box() const { return grid_.box(); }
  Vec<D> separation(const Real* x, std::size_t i, std::size_t j) const { return grid_.separation(x, i, j); }
  Real max_displacement_since_build(const Real* x) const {
    return grid() ? grid_.max_displacement_since_build(x) : tree_.max_displacement_since_build(x);
  }
  long allocations() const { return grid_.allocations() + tree_.allocations(); }
  NeighbourMethod method() const { return method_; }

 private:
  bool grid() const { return method_ == NeighbourMethod::cell_grid; }
  NeighbourSearch<D> grid_;
  KdTreeNeighbourSearch<D> tree_;
  Real crossover_;
  NeighbourMethod method_ = NeighbourMethod::cell_grid;
};

}  // namespace sphark
