#include "sphark/neighbours/spatial_order.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace sphark {

namespace {
// Row-major cell keys of the particles, cells of side `cell` from the lower corner of their
// bounding box (of the box along its periodic axes, positions wrapped into it); the cell count.
template <int D>
std::pair<std::vector<std::uint64_t>, std::uint64_t> cell_keys(const Real* x, std::size_t n, Real cell,
                                                                const std::optional<PeriodicBox<D>>& box) {
  if (!(cell > 0) || !std::isfinite(cell)) throw std::invalid_argument("cell_order: the cell side must be positive");
  std::vector<std::uint64_t> keys(n);
  if (n == 0) return {keys, 0};
  Vec<D> lo = Eigen::Map<const Vec<D>>(x), hi = lo;
  std::array<bool, D> wrap{};
  bool all_wrap = true;
  for (int k = 0; k < D; ++k) {
    wrap[k] = box && box->periodic[k];
    all_wrap = all_wrap && wrap[k];
  }
  if (!all_wrap)
    for (std::size_t i = 1; i < n; ++i) {
      lo = lo.cwiseMin(Eigen::Map<const Vec<D>>(x + D * i));
      hi = hi.cwiseMax(Eigen::Map<const Vec<D>>(x + D * i));
    }
  for (int k = 0; k < D; ++k)
    if (wrap[k]) lo[k] = box->lo[k], hi[k] = box->hi[k];
  std::array<std::uint64_t, D> cells{};
  Real total = 1;
  for (int k = 0; k < D; ++k) {
    cells[k] = static_cast<std::uint64_t>(std::floor((hi[k] - lo[k]) / cell)) + 1;
    total *= static_cast<Real>(cells[k]);
  }
  if (total >= 4294967296.0 || n >= 4294967296u) throw std::invalid_argument("cell_order: 2^32 cells or particles or more");
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t key = 0;
    for (int k = D - 1; k >= 0; --k) {
      Real s = x[D * i + k] - lo[k];
      if (wrap[k]) s -= (hi[k] - lo[k]) * std::floor(s / (hi[k] - lo[k]));
      const auto c = std::min(static_cast<std::uint64_t>(std::max(s / cell, Real(0))), cells[k] - 1);
      key = key * cells[k] + c;
    }
    keys[i] = key;
  }
  return {keys, static_cast<std::uint64_t>(total)};
}
}  // namespace

template <int D>
std::vector<std::size_t> cell_order(const Real* x, std::size_t n, Real cell, const std::optional<PeriodicBox<D>>& box) {
  std::vector<std::uint64_t> keyed = cell_keys<D>(x, n, cell, box).first;
  // (cell key << 32 | index): the index breaks ties, so the order is a function of x alone
  for (std::size_t i = 0; i < n; ++i) keyed[i] = keyed[i] << 32 | static_cast<std::uint64_t>(i);
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::size_t>(keyed[i] & 0xffffffffu);
  return order;
}

template <int D>
Real scrambled_fraction(const Real* x, std::size_t n, Real cell, const std::optional<PeriodicBox<D>>& box) {
  if (n < 2) return 0;
  auto [keys, cells] = cell_keys<D>(x, n, cell, box);
  std::size_t changes = 0;
#pragma omp parallel for schedule(static) reduction(+ : changes)
  for (std::size_t i = 1; i < n; ++i) changes += keys[i] != keys[i - 1];
  std::size_t occupied = 0;
  if (cells <= 4 * static_cast<std::uint64_t>(n)) {
    std::vector<std::uint8_t> seen(cells, 0);
    for (const std::uint64_t k : keys) occupied += !seen[k], seen[k] = 1;
  } else {  // sparse cells (a bounding box much larger than the particles' spread)
    std::sort(keys.begin(), keys.end());
    occupied = static_cast<std::size_t>(std::unique(keys.begin(), keys.end()) - keys.begin());
  }
  return static_cast<Real>(changes - (occupied - 1)) / static_cast<Real>(n - 1);
}

template std::vector<std::size_t> cell_order<2>(const Real*, std::size_t, Real, const std::optional<PeriodicBox<2>>&);
template std::vector<std::size_t> cell_order<3>(const Real*, std::size_t, Real, const std::optional<PeriodicBox<3>>&);
template Real scrambled_fraction<2>(const Real*, std::size_t, Real, const std::optional<PeriodicBox<2>>&);
template Real scrambled_fraction<3>(const Real*, std::size_t, Real, const std::optional<PeriodicBox<3>>&);

}  // namespace sphark
