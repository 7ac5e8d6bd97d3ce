#pragma once
// Fixed-radius neighbour search over a nanoflann kd-tree, with periodic images and compact
// (CSR) lists. nanoflann works with SQUARED radii and distances: that is handled here only.
//
// Reuse with a Verlet skin: build(x, n, radius + skin) once, then while
// max_displacement_since_build(x) < skin / 2 every pair closer than `radius` is still in the
// lists (each particle moved less than skin/2, so a pair closed in by less than skin).
// A rebuild reuses every buffer's capacity; only nanoflann's node pool is allocated again.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/neighbours/periodic_box.hpp"

namespace sphark {

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
  void build(const Real* x, std::size_t n, Real radius);

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

  // Largest |x_i - x_i(at build)| (minimum image), for the Verlet-skin validity check.
  Real max_displacement_since_build(const Real* x) const;

 private:
  struct Tree;
  std::optional<PeriodicBox<D>> box_;
  Real radius_ = 0;
  NeighbourList list_;
  std::vector<Real> points_;                // built points followed by periodic images (D each)
  std::vector<std::uint32_t> image_owner_;  // original index of each stored point
  std::size_t n_ = 0;
  std::unique_ptr<Tree> tree_;
  std::vector<std::vector<std::uint32_t>> scratch_;  // per-particle lists, capacity kept across builds
};

}  // namespace sphark
