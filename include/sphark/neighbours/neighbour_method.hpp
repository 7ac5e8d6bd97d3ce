#pragma once
// Which neighbour-list builder to use for a set of per-particle radii, and a search object that
// applies the rule at every build (both builders give identical lists).
//
// Predictor. The cell grid sizes its cells by the largest radius r_max, so particle i
// distance-tests the particles of 3^D cells of volume r_max^D, about (r_max / r_i)^D times more
// than inside its own radius; the kd-tree tests a bounded multiple of the pairs it lists.
// Their cost ratio therefore grows with
//   Q = mean_i (r_max / r_i)^D        (1 for equal radii)
// and the grid is chosen while Q stays below the measured crossover of its dimension (below;
// session 15's, before the vectorised scan: 3D grid/tree 0.72 at Q = 1, 1.34 at 3.5, 4.2 at 21,
// crossover Q = 2, docs/collapse_parts.md; it then used Q3 in 2D as well, which sent the late
// Orszag-Tang vortex to the tree where the grid is 1.4-2x faster).
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
// Re-measured in session 17, after the cell scan was vectorised (session 16; bench/neighbours_wide_h,
// 1 thread; the 2D scenes: a disc of density contrast c in the periodic unit square, 10^5 particles):
// 3D grid/tree 0.21 (Q = 1), 0.26 (1.66), 0.38 (3.5), 1.03 (20.6), 4.98 (205): crossover Q3 = 19;
// 2D grid/tree 0.47 (Q2 = 1), 0.57 (2.8), 0.60 (4.5), 0.73 (7.2), 1.07 (13.9): crossover Q2 = 12.
inline constexpr Real kGridCrossover3 = 19.0;
inline constexpr Real kGridCrossover2 = 12.0;

// Q = mean (r_max / r_i)^dim over the radii (capped at r_max, as the builders cap them); 1 without
// radii. In dim dimensions the grid's 3^dim cells of side r_max hold (r_max / r_i)^dim times the
// particles of the search volume of r_i.
Real cell_grid_overhead(const Real* radii, std::size_t n, Real r_max, int dim = 3);

// The measured crossovers of Q (bench/neighbours_wide_h, docs/performance.md "Which neighbour builder").
inline constexpr Real grid_crossover(int dim) { return dim == 3 ? kGridCrossover3 : kGridCrossover2; }

inline NeighbourMethod choose_neighbour_method(const Real* radii, std::size_t n, Real r_max, int dim = 3,
                                               Real crossover = -1) {
  if (crossover < 0) crossover = grid_crossover(dim);
  return cell_grid_overhead(radii, n, r_max, dim) < crossover ? NeighbourMethod::cell_grid : NeighbourMethod::kd_tree;
}

// NeighbourSearch's interface; each build picks the builder by the rule (without radii: the
// grid). The lists do not depend on the choice, so switching between builds is harmless.
template <int D>
class AdaptiveNeighbourSearch {
 public:
  explicit AdaptiveNeighbourSearch(std::optional<PeriodicBox<D>> box = std::nullopt, Real crossover = grid_crossover(D))
      : grid_(box), tree_(box), crossover_(crossover) {}

  // rows (<= n): the grid builds the rows of particles 0 .. rows - 1 only (a halo's stay empty);
  // the tree builds every row (the extra ones unused).
  void build(const Real* x, std::size_t n, Real radius, const std::uint32_t* key = nullptr,
             const Real* radii = nullptr, std::size_t rows = static_cast<std::size_t>(-1)) {
    method_ = radii ? choose_neighbour_method(radii, n, radius, D, crossover_) : NeighbourMethod::cell_grid;
    if (method_ == NeighbourMethod::cell_grid)
      grid_.build(x, n, radius, key, radii, rows);
    else
      tree_.build(x, n, radius, key, radii);
  }
  void renumber(const std::vector<std::uint32_t>& order) {
    if (method_ == NeighbourMethod::cell_grid)
      grid_.renumber(order);
    else
      tree_.renumber(order);
  }
  void keep(const std::vector<std::uint32_t>& kept) {
    if (method_ == NeighbourMethod::cell_grid)
      grid_.keep(kept);
    else
      tree_.keep(kept);
  }
  const std::vector<RowSpan>& row_spans() const { return grid() ? grid_.row_spans() : tree_.row_spans(); }
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
  void displacements_since_build(const Real* x, std::vector<Real>& out) const {
    if (grid())
      grid_.displacements_since_build(x, out);
    else
      tree_.displacements_since_build(x, out);
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
