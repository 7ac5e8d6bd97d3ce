#pragma once
// Fixed-radius neighbour search on a uniform cell grid (cell side >= radius; a particle's
// neighbours lie in its own and the 3^D surrounding cells, wrapped across periodic faces), with
// compact (CSR) lists. Periodic pairs are found by the minimum-image separation (the box must
// be at least 2 radii long along periodic axes, so that image is unique).
//
// Reuse with a Verlet skin: build(x, n, radius + skin) once, then while
// max_displacement_since_build(x) < skin / 2 every pair closer than `radius` is still in the
// lists (each particle moved less than skin/2, so a pair closed in by less than skin).
// A rebuild reuses every buffer's capacity: once the buffers have grown to the largest lists
// seen, a rebuild allocates nothing (allocations() counts the builds that had to grow one).
// The build is OpenMP-parallel over particles; the lists do not depend on the thread count.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/neighbours/periodic_box.hpp"

namespace sphark {

namespace neighbours_detail {  // the build's cell scan (src/neighbours/cell_scan.hpp)
template <int D>
struct CellPoints;
template <int D>
using ScanCell = std::uint32_t* (*)(const CellPoints<D>&, std::uint32_t, std::uint32_t, const Real*, Real, std::uint32_t,
                                    const MinimumImage<D>&, std::uint32_t*);
}  // namespace neighbours_detail

// Neighbours of particle i are indices[offsets[i] .. offsets[i+1]), sorted ascending, never i.
struct NeighbourList {
  std::vector<std::size_t> offsets;
  std::vector<std::uint32_t> indices;

  std::size_t particles() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::size_t begin(std::size_t i) const { return offsets[i]; }
  std::size_t end(std::size_t i) const { return offsets[i + 1]; }
  std::size_t count(std::size_t i) const { return offsets[i + 1] - offsets[i]; }
  std::size_t pairs() const { return indices.size(); }
};

// The least and largest particle index of a row and its owner: the span a loop over it reads.
using RowSpan = std::pair<std::uint32_t, std::uint32_t>;

// Row o of `list` renumbered into out (index j becomes inverse[j]); `self` is its new owner.
inline RowSpan renumber_row(const NeighbourList& list, std::size_t o, const std::uint32_t* inverse,
                            std::uint32_t self, std::uint32_t* out) {
  RowSpan span{self, self};
  for (std::size_t r = list.begin(o); r < list.end(o); ++r) {
    const std::uint32_t j = inverse[list.indices[r]];
    *out++ = j;
    span.first = std::min(span.first, j);
    span.second = std::max(span.second, j);
  }
  return span;
}

// Keeps the rows of the particles `kept` (ascending old indices; new index i = kept[i]), each
// without the particles not kept and renumbered, in its order; spans: each new row's RowSpan;
// inverse: old index -> new, kGoneParticle for the others.
inline constexpr std::uint32_t kGoneParticle = ~std::uint32_t{0};
void keep_rows(NeighbourList& list, const std::vector<std::uint32_t>& kept, std::vector<RowSpan>& spans,
               std::vector<std::uint32_t>& inverse);

template <int D>
class NeighbourSearch {
 public:
  explicit NeighbourSearch(std::optional<PeriodicBox<D>> box = std::nullopt);
  ~NeighbourSearch();
  NeighbourSearch(NeighbourSearch&&) noexcept;
  NeighbourSearch& operator=(NeighbourSearch&&) noexcept;

  // Lists every j != i with |x_i - x_j| < radius. x holds D values per particle (column-major
  // D x n, as vector_field<D> gives). Throws std::invalid_argument if a periodic box is shorter
  // than 2 * radius along a periodic axis (the minimum image would be ambiguous).
  // key (optional, n entries): each row is sorted ascending by key[j] instead of j (a caller
  // that stores particles in its own order keeps a fixed summation order this way).
  // radii (optional, n entries, each <= radius): lists every pair with
  // |x_i - x_j| < max(radii[i], radii[j]) instead (symmetric; radius sizes the cells).
  // rows (optional, <= n): only particles 0 .. rows - 1 get their rows; the others are found as
  // neighbours but their own rows stay empty (a distributed scheme's halo: docs/scaling.md).
  void build(const Real* x, std::size_t n, Real radius, const std::uint32_t* key = nullptr,
             const Real* radii = nullptr, std::size_t rows = static_cast<std::size_t>(-1));

  // Renumbers the built particles: new index i is old index order[i] (a permutation of 0..n-1).
  // The lists, the stored positions and the cells follow; every row keeps its order.
  void renumber(const std::vector<std::uint32_t>& order);
  // Removes the built particles not in `kept` (ascending; new index i is old index kept[i]): the
  // lists, the stored positions and the cells follow (particles leaving, e.g. accreted by a sink:
  // the others' lists stay valid, as a removal brings no pair closer).
  void keep(const std::vector<std::uint32_t>& kept);
  // After renumber(): per particle i, the least and largest index in {i} and its row (the span of
  // memory a loop over the row reads, in the new order); empty before.
  const std::vector<RowSpan>& row_spans() const { return spans_; }

  // The built particles in cell order (a spatial order: neighbours in space are near in it).
  const std::vector<std::uint32_t>& cell_order() const { return cell_particles_; }

  // Indices of the built particles within `radius` of point p (radius <= the build radius is
  // not required; images are searched when the box is periodic). Sorted ascending, unique.
  void query(const Vec<D>& p, Real radius, std::vector<std::uint32_t>& out) const;

  const NeighbourList& list() const { return list_; }
  Real radius() const { return radius_; }
  const std::optional<PeriodicBox<D>>& box() const { return box_; }

  // x_i - x_j with the minimum-image convention when periodic.
  Vec<D> separation(const Real* x, std::size_t i, std::size_t j) const {
    Vec<D> d = Eigen::Map<const Vec<D>>(x + D * i) - Eigen::Map<const Vec<D>>(x + D * j);
    return box_ ? box_->minimum_image(d) : d;
  }

  // Largest |x_i - x_i(at build)| (minimum image), for the Verlet-skin validity check; with
  // `order`, x_i is particle order[i] of x (x in the order before renumber(order)).
  Real max_displacement_since_build(const Real* x, const std::uint32_t* order = nullptr) const;
  void displacements_since_build(const Real* x, std::vector<Real>& out) const;  // per particle

  // Builds so far that had to enlarge a buffer (the others allocated nothing).
  long allocations() const { return allocations_; }

 private:
  void bin(std::size_t n, Real radius);  // the cell grid of points_
  // The parts of build(): its argument checks, the capacity of every buffer (a change counts as
  // an allocation), one particle's row, the thread rows joined into list_.
  void check_build(std::size_t n, Real radius) const;
  std::size_t capacity() const;
  neighbours_detail::CellPoints<D> fill_cell_points(const Real* r2i);
  struct SlotRange {
    std::uint32_t begin, end;
  };
  static constexpr int kStencilRows = D == 1 ? 1 : D == 2 ? 3 : 9;  // 3^(D-1)
  int stencil_ranges(std::size_t i, std::array<SlotRange, kStencilRows * 3>& ranges) const;
  std::size_t append_row(std::size_t i, const MinimumImage<D>& image, Real r2max, const Real* r2i, const std::uint32_t* key,
                         const neighbours_detail::CellPoints<D>& cells, neighbours_detail::ScanCell<D> scan,
                         std::vector<std::uint32_t>& out, std::size_t len) const;
  void join_rows(const std::vector<std::uint32_t>* rows, int team, std::size_t with_rows);  // rows 0 .. with_rows - 1 built

  std::optional<PeriodicBox<D>> box_;
  Real radius_ = 0;
  NeighbourList list_;
  std::vector<Real> points_;  // the built points (D each), wrapped into the box along periodic axes
  std::size_t n_ = 0;
  // Cell grid: cells_[k] per axis, side side_[k] from origin_; particles of cell c are
  // cell_particles_[cell_start_[c] .. cell_start_[c+1]), ascending.
  std::array<std::size_t, D> cells_{};
  Vec<D> origin_ = Vec<D>::Zero(), side_ = Vec<D>::Ones();
  std::vector<std::uint32_t> cell_of_, cell_start_, cell_particles_;
  std::vector<std::vector<std::uint32_t>> thread_lists_;  // per-thread rows (their size: room, not length), kept
  std::vector<std::uint32_t> inverse_, swap_u32_;         // renumber() scratch
  std::vector<RowSpan> spans_;                            // row_spans()
  std::vector<std::size_t> swap_offsets_;
  std::vector<Real> swap_points_;
  std::vector<Real> radius2_;  // per-particle squared radii of the last build (if given)
  std::vector<Real> cell_points_, cell_r2_;  // build scratch: positions (one array per axis) and r2 in cell order
  long allocations_ = 0;
};

}  // namespace sphark
