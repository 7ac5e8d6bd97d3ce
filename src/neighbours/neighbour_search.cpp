#include "sphark/neighbours/neighbour_search.hpp"

#include "sphark/neighbours/displacement.hpp"

#include "cell_scan.hpp"
#include "row_sort.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace sphark {

template <int D>
NeighbourSearch<D>::NeighbourSearch(std::optional<PeriodicBox<D>> box) : box_(std::move(box)) {}
template <int D>
NeighbourSearch<D>::~NeighbourSearch() = default;
template <int D>
NeighbourSearch<D>::NeighbourSearch(NeighbourSearch&&) noexcept = default;
template <int D>
NeighbourSearch<D>& NeighbourSearch<D>::operator=(NeighbourSearch&&) noexcept = default;

// Cell grid over the box (periodic axes) or the bounding box (open axes): floor(extent / radius)
// cells per axis (at least 1; fewer when the grid would have far more cells than particles),
// so every cell side is >= radius. Counting sort by cell keeps particles ascending per cell.
template <int D>
void NeighbourSearch<D>::bin(std::size_t n, Real radius) {
  Vec<D> lo = Vec<D>::Zero(), hi = Vec<D>::Zero();
  for (int k = 0; k < D; ++k) {
    if (box_ && box_->periodic[k]) {
      lo[k] = box_->lo[k];
      hi[k] = box_->hi[k];
      continue;
    }
    lo[k] = hi[k] = n > 0 ? points_[k] : 0;
    for (std::size_t i = 1; i < n; ++i) {
      lo[k] = std::min(lo[k], points_[D * i + k]);
      hi[k] = std::max(hi[k], points_[D * i + k]);
    }
  }
  double total = 1;
  for (int k = 0; k < D; ++k) {
    const Real extent = hi[k] - lo[k];
    cells_[k] = extent > radius ? static_cast<std::size_t>(std::min(extent / radius, 1e6)) : 1;
    total *= static_cast<double>(cells_[k]);
  }
  const double budget = 4.0 * static_cast<double>(n) + 64;  // sparse sets: coarser cells
  if (total > budget) {
    const double f = std::pow(total / budget, 1.0 / D);
    for (int k = 0; k < D; ++k) cells_[k] = std::max<std::size_t>(1, static_cast<std::size_t>(cells_[k] / f));
  }
  std::size_t ncell = 1;
  for (int k = 0; k < D; ++k) {
    ncell *= cells_[k];
    side_[k] = hi[k] > lo[k] ? (hi[k] - lo[k]) / static_cast<Real>(cells_[k]) : 1;
  }
  origin_ = lo;
  cell_of_.resize(n);
  cell_start_.assign(ncell + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t c = 0;
    for (int k = D - 1; k >= 0; --k) {
      const Real s = std::floor((points_[D * i + k] - origin_[k]) / side_[k]);
      const std::size_t ck = s <= 0 ? 0 : std::min(cells_[k] - 1, static_cast<std::size_t>(s));
      c = c * cells_[k] + ck;
    }
    cell_of_[i] = static_cast<std::uint32_t>(c);
    ++cell_start_[c + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_particles_.resize(n);
  // fill with a running cursor per cell (cell_start_ shifted, then restored)
  for (std::size_t i = 0; i < n; ++i) cell_particles_[cell_start_[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
  for (std::size_t c = ncell; c > 0; --c) cell_start_[c] = cell_start_[c - 1];
  cell_start_[0] = 0;
}

// The positions (and squared radii) of the binned particles in cell order, one array per axis:
// what the rows' cell scans read (cell_scan.hpp).
template <int D>
neighbours_detail::CellPoints<D> NeighbourSearch<D>::fill_cell_points(const Real* r2i) {
  const std::size_t n = n_;
  cell_points_.resize(D * n);
  cell_r2_.resize(r2i ? n : 0);
  for (std::size_t s = 0; s < n; ++s) {
    const std::uint32_t j = cell_particles_[s];
    for (int k = 0; k < D; ++k) cell_points_[k * n + s] = points_[D * j + k];
    if (r2i) cell_r2_[s] = r2i[j];
  }
  neighbours_detail::CellPoints<D> c{};
  for (int k = 0; k < D; ++k) c.x[k] = cell_points_.data() + k * n;
  c.r2 = r2i ? cell_r2_.data() : nullptr;
  c.particle = cell_particles_.data();
  return c;
}

template <int D>
void NeighbourSearch<D>::check_build(std::size_t n, Real radius) const {
  if (!(radius > 0)) throw std::invalid_argument("NeighbourSearch::build: radius must be positive");
  if (n >= (std::size_t{1} << 31)) throw std::invalid_argument("NeighbourSearch::build: too many particles");
  if (box_) {
    const Vec<D> L = box_->length();
    for (int k = 0; k < D; ++k)
      if (box_->periodic[k] && L[k] < 2 * radius)
        throw std::invalid_argument("NeighbourSearch: periodic box length " + std::to_string(L[k]) + " along axis " +
                                    std::to_string(k) + " is shorter than twice the search radius " +
                                    std::to_string(radius));
  }
}

template <int D>
std::size_t NeighbourSearch<D>::capacity() const {
  std::size_t c = points_.capacity() + list_.offsets.capacity() + list_.indices.capacity() + radius2_.capacity() +
                  cell_points_.capacity() + cell_r2_.capacity() +
                  cell_of_.capacity() + cell_start_.capacity() + cell_particles_.capacity();
  for (const auto& t : thread_lists_) c += t.capacity();
  return c;
}

// The slot ranges of the cells next to particle i's cell (its own included; wrapped when periodic):
// the cells adjacent along axis 0 are consecutive in slot order, so each row of the stencil along
// axis 0 is one range unless it wraps. Returns how many ranges.
template <int D>
int NeighbourSearch<D>::stencil_ranges(std::size_t i, std::array<SlotRange, kStencilRows * 3>& ranges) const {
  std::array<std::array<std::size_t, 3>, D> near{};
  std::array<int, D> count{};
  std::size_t ci = cell_of_[i];
  for (int k = 0; k < D; ++k) {
    const std::size_t c = ci % cells_[k], nc = cells_[k];
    ci /= cells_[k];
    const bool periodic = box_ && box_->periodic[k];
    int m = 0;
    if (periodic && nc <= 3) {
      for (std::size_t j = 0; j < nc; ++j) near[k][m++] = j;
    } else {
      if (c > 0) near[k][m++] = c - 1; else if (periodic) near[k][m++] = nc - 1;
      near[k][m++] = c;
      if (c + 1 < nc) near[k][m++] = c + 1; else if (periodic) near[k][m++] = 0;
    }
    count[k] = m;
  }
  int n = 0;
  std::array<int, D> idx{};
  while (true) {
    std::size_t cell = 0;
    for (int k = D - 1; k >= 0; --k) cell = cell * cells_[k] + near[k][idx[k]];
    const SlotRange r{cell_start_[cell], cell_start_[cell + 1]};
    const bool next_along_axis0 = idx[0] > 0 && near[0][idx[0]] == near[0][idx[0] - 1] + 1;
    if (next_along_axis0) ranges[n - 1].end = r.end;
    else ranges[n++] = r;
    int k = 0;
    for (; k < D; ++k) {
      if (++idx[k] < count[k]) break;
      idx[k] = 0;
    }
    if (k == D) break;
  }
  return n;
}

// Appends particle i's neighbours to out[len ...) (grown when the candidates need room): those
// within r2max (or, with r2i, the larger of the two particles' squared radii), ascending in key
// (or in index). Returns the new length.
template <int D>
std::size_t NeighbourSearch<D>::append_row(std::size_t i, const MinimumImage<D>& image, Real r2max, const Real* r2i,
                                           const std::uint32_t* key, const neighbours_detail::CellPoints<D>& cells,
                                           neighbours_detail::ScanCell<D> scan, std::vector<std::uint32_t>& out,
                                           std::size_t len) const {
  std::array<SlotRange, kStencilRows * 3> ranges;
  const int n = stencil_ranges(i, ranges);
  std::size_t candidates = 0;
  for (int r = 0; r < n; ++r) candidates += ranges[r].end - ranges[r].begin;
  if (out.size() < len + candidates) out.resize(std::max(len + candidates, 2 * out.size()));
  const Real r2_i = r2i ? r2i[i] : r2max;
  const Real* xi = points_.data() + D * i;
  std::uint32_t* const row = out.data() + len;
  std::uint32_t* end = row;
  for (int r = 0; r < n; ++r)
    end = scan(cells, ranges[r].begin, ranges[r].end, xi, r2_i, static_cast<std::uint32_t>(i), image, end);
  neighbours_detail::sort_row(row, end, key);  // ascending: a deterministic summation order
  return len + static_cast<std::size_t>(end - row);
}

// The offsets from the row lengths, then each thread's rows copied to their place in the list.
template <int D>
void NeighbourSearch<D>::join_rows(const std::vector<std::uint32_t>* rows, int team, std::size_t with_rows) {
  const std::size_t n = n_;
  for (std::size_t i = 0; i < n; ++i) list_.offsets[i + 1] += list_.offsets[i];
  const std::size_t pairs = list_.offsets[n];
  if (pairs > list_.indices.capacity()) list_.indices.reserve(pairs + pairs / 8);  // headroom for later builds
  list_.indices.resize(pairs);
#pragma omp parallel for schedule(static, 1)
  for (int t = 0; t < team; ++t) {  // thread t's rows: rows[t][0 .. its rows' length)
    const std::size_t first = list_.offsets[with_rows * t / team], end = list_.offsets[with_rows * (t + 1) / team];
    std::copy_n(rows[t].begin(), end - first, list_.indices.begin() + static_cast<std::ptrdiff_t>(first));
  }
}

template <int D>
void NeighbourSearch<D>::build(const Real* x, std::size_t n, Real radius, const std::uint32_t* key,
                               const Real* radii, std::size_t rows_wanted) {
  check_build(n, radius);
  const std::size_t with_rows = std::min(rows_wanted, n);
  const std::size_t capacity_before = capacity();

  radius_ = radius;
  n_ = n;
  points_.resize(D * n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<D> xi = Eigen::Map<const Vec<D>>(x + D * i);
    Eigen::Map<Vec<D>>(points_.data() + D * i) = box_ ? box_->wrap(xi) : xi;
  }
  bin(n, radius);

  const int max_threads = omp_get_max_threads();
  if (thread_lists_.size() < static_cast<std::size_t>(max_threads)) thread_lists_.resize(max_threads);
  list_.offsets.resize(n + 1);
  list_.offsets[0] = 0;
  const Real r2max = radius * radius;
  const MinimumImage<D> image(box_);
  if (radii) {
    radius2_.resize(n);
    for (std::size_t i = 0; i < n; ++i) radius2_[i] = std::min(radii[i], radius) * std::min(radii[i], radius);
  }
  const Real* r2i = radii ? radius2_.data() : nullptr;
  const neighbours_detail::CellPoints<D> cells = fill_cell_points(r2i);
  const neighbours_detail::ScanCell<D> scan = neighbours_detail::scan_cell_for_this_cpu<D>();
  std::vector<std::uint32_t>* rows = thread_lists_.data();
  int team = 1;
#pragma omp parallel
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
#pragma omp single
    team = nt;
    // Contiguous chunk per thread: the rows of a thread are consecutive in the final list.
    const std::size_t first = with_rows * t / nt, last = with_rows * (t + 1) / nt;
    std::size_t len = 0;
    for (std::size_t i = first; i < last; ++i) {
      const std::size_t row_start = len;
      len = append_row(i, image, r2max, r2i, key, cells, scan, rows[t], len);
      list_.offsets[i + 1] = len - row_start;
    }
  }
  std::fill(list_.offsets.begin() + static_cast<std::ptrdiff_t>(with_rows) + 1, list_.offsets.end(), 0);  // empty rows
  join_rows(rows, team, with_rows);
  if (capacity() != capacity_before) ++allocations_;
}

template <int D>
void NeighbourSearch<D>::renumber(const std::vector<std::uint32_t>& order) {
  const std::size_t n = n_;
  if (order.size() != n) throw std::invalid_argument("NeighbourSearch::renumber: order must have one entry per particle");
  inverse_.resize(n);
  for (std::size_t i = 0; i < n; ++i) inverse_[order[i]] = static_cast<std::uint32_t>(i);
  swap_points_.resize(D * n);
  swap_offsets_.resize(n + 1);
  swap_u32_.resize(std::max(list_.indices.size(), n));
  spans_.resize(n);
  swap_offsets_[0] = 0;
  for (std::size_t i = 0; i < n; ++i) swap_offsets_[i + 1] = swap_offsets_[i] + list_.count(order[i]);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t o = order[i];
    for (int k = 0; k < D; ++k) swap_points_[D * i + k] = points_[D * o + k];
    spans_[i] = renumber_row(list_, o, inverse_.data(), static_cast<std::uint32_t>(i), &swap_u32_[swap_offsets_[i]]);
  }
  std::copy(swap_points_.begin(), swap_points_.end(), points_.begin());
  std::copy(swap_offsets_.begin(), swap_offsets_.end(), list_.offsets.begin());
  std::copy(swap_u32_.begin(), swap_u32_.begin() + list_.indices.size(), list_.indices.begin());  // (swap_u32_ may be longer)
  // cells: the particles of a cell, renamed (and sorted again, as bin() leaves them)
  for (auto& c : cell_particles_) c = inverse_[c];
  for (std::size_t c = 0; c + 1 < cell_start_.size(); ++c)
    std::sort(cell_particles_.begin() + cell_start_[c], cell_particles_.begin() + cell_start_[c + 1]);
  for (std::size_t i = 0; i < n; ++i) swap_u32_[i] = cell_of_[order[i]];
  std::copy(swap_u32_.begin(), swap_u32_.begin() + n, cell_of_.begin());
}

void keep_rows(NeighbourList& list, const std::vector<std::uint32_t>& kept, std::vector<RowSpan>& spans,
               std::vector<std::uint32_t>& inverse) {
  inverse.assign(list.particles(), kGoneParticle);
  for (std::size_t i = 0; i < kept.size(); ++i) inverse.at(kept[i]) = static_cast<std::uint32_t>(i);
  std::vector<std::size_t> offsets(kept.size() + 1, 0);
  spans.resize(kept.size());
  std::size_t w = 0;  // rows only move forward: compacted in place
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const std::uint32_t self = static_cast<std::uint32_t>(i);
    RowSpan span{self, self};
    for (std::size_t k = list.begin(kept[i]); k < list.end(kept[i]); ++k) {
      const std::uint32_t j = inverse[list.indices[k]];
      if (j == kGoneParticle) continue;
      list.indices[w++] = j;
      span.first = std::min(span.first, j);
      span.second = std::max(span.second, j);
    }
    offsets[i + 1] = w;
    spans[i] = span;
  }
  list.indices.resize(w);
  list.offsets = std::move(offsets);
}

template <int D>
void NeighbourSearch<D>::keep(const std::vector<std::uint32_t>& kept) {
  keep_rows(list_, kept, spans_, inverse_);
  for (std::size_t i = 0; i < kept.size(); ++i) {
    for (int k = 0; k < D; ++k) points_[D * i + k] = points_[D * kept[i] + k];
    cell_of_[i] = cell_of_[kept[i]];
    if (!radius2_.empty()) radius2_[i] = radius2_[kept[i]];
  }
  points_.resize(D * kept.size());
  cell_of_.resize(kept.size());
  if (!radius2_.empty()) radius2_.resize(kept.size());
  std::size_t w = 0;  // each cell's particles, renamed, ascending still
  for (std::size_t c = 0; c + 1 < cell_start_.size(); ++c) {
    const std::size_t begin = cell_start_[c], end = cell_start_[c + 1];
    cell_start_[c] = static_cast<std::uint32_t>(w);
    for (std::size_t k = begin; k < end; ++k)
      if (inverse_[cell_particles_[k]] != kGoneParticle) cell_particles_[w++] = inverse_[cell_particles_[k]];
  }
  if (!cell_start_.empty()) cell_start_.back() = static_cast<std::uint32_t>(w);
  cell_particles_.resize(w);
  n_ = kept.size();
}

template <int D>
void NeighbourSearch<D>::query(const Vec<D>& p, Real radius, std::vector<std::uint32_t>& out) const {
  out.clear();
  if (list_.offsets.empty()) throw std::logic_error("NeighbourSearch::query before build");
  if (box_ && radius > radius_)
    throw std::invalid_argument("NeighbourSearch::query: periodic query radius exceeds the build radius");
  for (std::size_t j = 0; j < n_; ++j) {  // O(n): a query is not a hot path
    Vec<D> d = p - Eigen::Map<const Vec<D>>(points_.data() + D * j);
    if (box_) d = box_->minimum_image(d);
    if (d.squaredNorm() < radius * radius) out.push_back(static_cast<std::uint32_t>(j));
  }
}

template <int D>
Real NeighbourSearch<D>::max_displacement_since_build(const Real* x, const std::uint32_t* order) const {
  return max_displacement<D>(x, points_.data(), n_, box_, order);
}

template <int D>
void NeighbourSearch<D>::displacements_since_build(const Real* x, std::vector<Real>& out) const {
  displacements<D>(x, points_.data(), n_, box_, out);
}

template class NeighbourSearch<1>;
template class NeighbourSearch<2>;
template class NeighbourSearch<3>;

}  // namespace sphark
