#include "sphark/neighbours/neighbour_search.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include <nanoflann.hpp>

namespace sphark {

namespace {
// nanoflann dataset adaptor over a flat array of D-vectors.
template <int D>
struct PointCloud {
  const std::vector<Real>* pts = nullptr;
  std::size_t kdtree_get_point_count() const { return pts->size() / D; }
  Real kdtree_get_pt(std::size_t i, std::size_t k) const { return (*pts)[D * i + k]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const { return false; }
};
}  // namespace

template <int D>
struct NeighbourSearch<D>::Tree {
  using Metric = nanoflann::L2_Simple_Adaptor<Real, PointCloud<D>>;
  using KdTree = nanoflann::KDTreeSingleIndexAdaptor<Metric, PointCloud<D>, D, std::uint32_t>;
  PointCloud<D> cloud;
  KdTree index;
  explicit Tree(const std::vector<Real>* pts)
      : cloud{pts}, index(D, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}

  // The one place where radii become squared radii.
  void within(const Real* p, Real radius, std::vector<std::pair<std::uint32_t, Real>>& hits) const {
    index.radiusSearch(p, radius * radius, hits, nanoflann::SearchParams(32, 0.0f, false));
  }
};

template <int D>
NeighbourSearch<D>::NeighbourSearch(std::optional<PeriodicBox<D>> box) : box_(std::move(box)) {}
template <int D>
NeighbourSearch<D>::~NeighbourSearch() = default;
template <int D>
NeighbourSearch<D>::NeighbourSearch(NeighbourSearch&&) noexcept = default;
template <int D>
NeighbourSearch<D>& NeighbourSearch<D>::operator=(NeighbourSearch&&) noexcept = default;

template <int D>
void NeighbourSearch<D>::build(const Real* x, std::size_t n, Real radius) {
  if (!(radius > 0)) throw std::invalid_argument("NeighbourSearch::build: radius must be positive");
  if (n >= (std::size_t{1} << 31)) throw std::invalid_argument("NeighbourSearch::build: too many particles");
  radius_ = radius;
  n_ = n;
  points_.assign(x, x + D * n);  // keeps capacity: images are appended below
  image_owner_.resize(n);
  for (std::size_t i = 0; i < n; ++i) image_owner_[i] = static_cast<std::uint32_t>(i);

  // Periodic images of the particles within `radius` of a periodic face (all face, edge and
  // corner combinations), so that a plain Euclidean search finds minimum-image neighbours.
  if (box_) {
    const Vec<D> L = box_->length();
    for (int k = 0; k < D; ++k)
      if (box_->periodic[k] && L[k] < 2 * radius)
        throw std::invalid_argument("NeighbourSearch: periodic box length " + std::to_string(L[k]) + " along axis " +
                                    std::to_string(k) + " is shorter than twice the search radius " +
                                    std::to_string(radius));
    std::vector<Real>& pts = points_;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec<D> xi = box_->wrap(Eigen::Map<const Vec<D>>(x + D * i));
      Eigen::Map<Vec<D>>(pts.data() + D * i) = xi;
      std::array<int, D> shifts_lo{}, shifts_hi{};
      for (int k = 0; k < D; ++k) {
        shifts_lo[k] = shifts_hi[k] = 0;
        if (!box_->periodic[k]) continue;
        if (xi[k] - box_->lo[k] < radius) shifts_hi[k] = 1;   // image at x + L
        if (box_->hi[k] - xi[k] < radius) shifts_lo[k] = -1;  // image at x - L
      }
      // enumerate every combination of shifts in {lo..hi} per axis except all-zero
      std::array<int, D> s = shifts_lo;
      while (true) {
        bool zero = true;
        for (int k = 0; k < D; ++k) zero = zero && s[k] == 0;
        if (!zero) {
          Vec<D> img = xi;
          for (int k = 0; k < D; ++k) img[k] += s[k] * L[k];
          for (int k = 0; k < D; ++k) pts.push_back(img[k]);
          image_owner_.push_back(static_cast<std::uint32_t>(i));
        }
        int k = 0;
        for (; k < D; ++k) {
          if (s[k] < shifts_hi[k]) {
            ++s[k];
            break;
          }
          s[k] = shifts_lo[k];
        }
        if (k == D) break;
      }
    }
  }
  if (!tree_) tree_ = std::make_unique<Tree>(&points_);
  tree_->cloud.pts = &points_;  // this object may have been moved since the last build
  tree_->index.buildIndex();

  // Pass 1: count; pass 2: fill. Each particle's list is sorted, so output is deterministic.
  list_.offsets.assign(n + 1, 0);
  std::vector<std::vector<std::uint32_t>>& per_particle = scratch_;
  if (per_particle.size() < n) per_particle.resize(n);
#pragma omp parallel
  {
    std::vector<std::pair<std::uint32_t, Real>> hits;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      tree_->within(points_.data() + D * i, radius, hits);
      auto& out = per_particle[i];
      out.clear();
      out.reserve(hits.size());
      for (const auto& h : hits) {
        const std::uint32_t j = image_owner_[h.first];
        if (j != i) out.push_back(j);
      }
      std::sort(out.begin(), out.end());
    }
  }
  for (std::size_t i = 0; i < n; ++i) list_.offsets[i + 1] = list_.offsets[i] + per_particle[i].size();
  list_.indices.resize(list_.offsets[n]);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    std::copy(per_particle[i].begin(), per_particle[i].end(), list_.indices.begin() + list_.offsets[i]);
}

template <int D>
void NeighbourSearch<D>::query(const Vec<D>& p, Real radius, std::vector<std::uint32_t>& out) const {
  out.clear();
  if (!tree_) throw std::logic_error("NeighbourSearch::query before build");
  tree_->cloud.pts = &points_;
  std::vector<std::pair<std::uint32_t, Real>> hits;
  const Vec<D> q = box_ ? box_->wrap(p) : p;
  if (box_ && radius > radius_)
    throw std::invalid_argument("NeighbourSearch::query: periodic query radius exceeds the build radius");
  tree_->within(q.data(), radius, hits);
  for (const auto& h : hits) out.push_back(image_owner_[h.first]);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

template <int D>
Real NeighbourSearch<D>::max_displacement_since_build(const Real* x) const {
  Real m2 = 0;
#pragma omp parallel for reduction(max : m2) schedule(static)
  for (std::size_t i = 0; i < n_; ++i) {
    Vec<D> d = Eigen::Map<const Vec<D>>(x + D * i) - Eigen::Map<const Vec<D>>(points_.data() + D * i);
    if (box_) d = box_->minimum_image(d);
    m2 = std::max(m2, d.squaredNorm());
  }
  return std::sqrt(m2);
}

template class NeighbourSearch<1>;
template class NeighbourSearch<2>;
template class NeighbourSearch<3>;

}  // namespace sphark
