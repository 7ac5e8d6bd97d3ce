// kd-tree build and node moments (see sphark/gravity/gravity_tree.hpp).
#include "sphark/gravity/gravity_tree.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <stdexcept>

#include "reuse_buffer.hpp"

namespace sphark {

using gravity_detail::resize_reporting_growth;

std::uint32_t left_count(std::uint32_t n, std::uint32_t leaf_size) {
  const std::uint32_t leaves = (n + leaf_size - 1) / leaf_size;
  return (leaves + 1) / 2 * leaf_size;
}

std::uint32_t tree_node_count(std::uint32_t n, std::uint32_t leaf_size) {
  if (n <= leaf_size) return 1;
  const std::uint32_t left = left_count(n, leaf_size);
  return 1 + tree_node_count(left, leaf_size) + tree_node_count(n - left, leaf_size);
}

void GravityTree::build(const GravitySources& src, Real support, int leaf_size) {
  if (leaf_size < 1) throw std::invalid_argument("GravityTree: leaf_size must be >= 1");
  if (src.n >= std::numeric_limits<std::uint32_t>::max()) throw std::invalid_argument("GravityTree: too many particles");
  const auto n = static_cast<std::uint32_t>(src.n);
  bool grew = resize_reporting_growth(order_, n);
  grew |= resize_reporting_growth(points_, n);
  const auto np = static_cast<std::ptrdiff_t>(n);
  // Warm start: the last build's order (a permutation of the same n particles), in which most
  // nodes' splits still stand; else the input order. The tree does not depend on it (split).
  warm_ = !grew && built_for_ == n && built_leaf_size_ == leaf_size;
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = 0; k < np; ++k) {
    const std::uint32_t a = warm_ ? points_[k].index : static_cast<std::uint32_t>(k);
    points_[k] = {{src.x[3 * a], src.x[3 * a + 1], src.x[3 * a + 2]}, a};
  }
  built_for_ = n, built_leaf_size_ = leaf_size;
  grew |= resize_reporting_growth(nodes_, n == 0 ? 0 : tree_node_count(n, static_cast<std::uint32_t>(leaf_size)));
  if (!warm_) plane_.assign(nodes_.size(), Plane{});
  for (auto* v : {&px_, &py_, &pz_, &pm_, &ph_, &phinv_}) grew |= resize_reporting_growth(*v, n);
  leaves_.clear();
  level_.clear();
  if (n > 0) {
    nodes_[0] = TreeNode{};
    nodes_[0].end = n;
    level_.assign(1, 0u);
  }
  while (!level_.empty()) {
    const auto count = static_cast<std::ptrdiff_t>(level_.size());
#pragma omp parallel for schedule(dynamic, 1)
    for (std::ptrdiff_t k = 0; k < count; ++k) split(level_[k], leaf_size);
    next_level_.clear();
    for (std::uint32_t i : level_) {
      if (nodes_[i].leaf()) continue;
      next_level_.push_back(nodes_[i].left);
      next_level_.push_back(nodes_[i].right);
    }
    std::swap(level_, next_level_);
  }
  for (std::uint32_t i = 0; i < nodes_.size(); ++i)
    if (nodes_[i].leaf()) leaves_.push_back(i);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = 0; k < np; ++k) {
    const std::uint32_t a = order_[k] = points_[k].index;
    px_[k] = points_[k].x[0], py_[k] = points_[k].x[1], pz_[k] = points_[k].x[2];
    pm_[k] = src.m[a], ph_[k] = src.h[a], phinv_[k] = 1 / src.h[a];
  }
  const auto nn = static_cast<std::ptrdiff_t>(nodes_.size());
#pragma omp parallel for schedule(dynamic, 8)
  for (std::ptrdiff_t i = 0; i < nn; ++i) compute_moments(static_cast<std::uint32_t>(i), support);
  if (grew) ++allocations_;
}

namespace {
// The build's order along an axis: coordinate, ties by particle index (a strict order).
template <class Point>
bool before(const Point& a, const Point& b, int axis) {
  return a.x[axis] < b.x[axis] || (a.x[axis] == b.x[axis] && a.index < b.index);
}

// The k-th (1-based) largest of the points with `below` (or else the k-th smallest of the others)
// in the order along `axis`, by one pass with the k best kept sorted in `best` (k small).
template <class It, class Point = typename std::iterator_traits<It>::value_type>
Point kth_nearest_the_plane(It first, It last, int axis, Real plane, bool below, std::size_t k, std::vector<Point>& best) {
  const auto nearer = [&](const Point& a, const Point& b) { return below ? before(b, a, axis) : before(a, b, axis); };
  best.clear();
  for (auto p = first; p != last; ++p) {
    if ((p->x[axis] < plane) != below || (best.size() == k && !nearer(*p, best.back()))) continue;
    if (best.size() == k) best.pop_back();
    best.insert(std::upper_bound(best.begin(), best.end(), *p, nearer), *p);
  }
  return best.back();
}
}  // namespace

// A warm split: the points of [first, last) on the left side of the node's last plane go left,
// give or take the few nearest it that make the left count `half` (up to kMaxPlaneSurplus; else
// false and nothing moves). Points cross only where they must: each one on the wrong side swaps
// with one on the other (most of each child's points keep their places for its own split).
bool GravityTree::split_at_plane(std::vector<BuildPoint>::iterator first, std::uint32_t half,
                                 std::vector<BuildPoint>::iterator last, Plane& plane) {
  constexpr std::ptrdiff_t kMaxPlaneSurplus = 64;
  const int axis = plane.axis;
  const Real s = plane.at;
  std::ptrdiff_t below = 0;
  for (auto p = first; p != last; ++p) below += p->x[axis] < s;
  const std::ptrdiff_t surplus = below - static_cast<std::ptrdiff_t>(half);
  if (surplus > kMaxPlaneSurplus || surplus < -kMaxPlaneSurplus) return false;
  thread_local std::vector<BuildPoint> best;
  BuildPoint edge{};
  if (surplus != 0) edge = kth_nearest_the_plane(first, last, axis, s, surplus > 0, static_cast<std::size_t>(std::abs(surplus)), best);
  const auto goes_left = [&](const BuildPoint& p) {
    if (surplus > 0) return p.x[axis] < s && before(p, edge, axis);   // all below but the surplus nearest
    if (surplus < 0) return p.x[axis] < s || !before(edge, p, axis);  // all below and the deficit nearest above
    return p.x[axis] < s;
  };
  auto l = first, r = first + half;
  for (;; ++l, ++r) {
    while (l != first + half && goes_left(*l)) ++l;
    while (r != last && !goes_left(*r)) ++r;
    if (l == first + half || r == last) break;
    std::iter_swap(l, r);
  }
  plane.at = surplus > 0 ? edge.x[axis] : surplus < 0 ? std::nextafter(edge.x[axis], std::numeric_limits<Real>::infinity()) : s;
  return true;
}

// Split along the longest side of the bounding box: the left child takes the left_count points
// first in the order (coordinate, particle index) — a strict order, so the split, and with leaves
// sorted by particle index the whole tree, follow from the positions alone, whatever order the
// points come in. The points carry their coordinates (no indirection). On a warm start along the
// axis of the node's last split, from that split's plane (split_at_plane); else nth_element.
// The children's slots in pre-order.
void GravityTree::split(std::uint32_t node, int leaf_size) {
  TreeNode& nd = nodes_[node];
  const std::uint32_t count = nd.count();
  const auto first = points_.begin() + nd.begin, last = points_.begin() + nd.end;
  if (count <= static_cast<std::uint32_t>(leaf_size)) {
    nd.left = nd.right = 0;
    std::sort(first, last, [](const BuildPoint& a, const BuildPoint& b) { return a.index < b.index; });
    return;
  }
  Real lo[3], hi[3];
  for (int c = 0; c < 3; ++c) lo[c] = hi[c] = first->x[c];
  for (auto p = first; p != last; ++p)
    for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], p->x[c]), hi[c] = std::max(hi[c], p->x[c]);
  int axis = 0;
  for (int c = 1; c < 3; ++c)
    if (hi[c] - lo[c] > hi[axis] - lo[axis]) axis = c;
  const std::uint32_t half = left_count(count, static_cast<std::uint32_t>(leaf_size));
  Plane& plane = plane_[node];
  if (!(warm_ && plane.axis == axis && split_at_plane(first, half, last, plane))) {
    std::nth_element(first, first + half, last, [axis](const BuildPoint& a, const BuildPoint& b) { return before(a, b, axis); });
    plane = {first[half].x[axis], static_cast<std::int8_t>(axis)};  // the right side: at or above it
  }
  nd.left = node + 1;
  nd.right = node + 1 + tree_node_count(half, static_cast<std::uint32_t>(leaf_size));
  TreeNode& l = nodes_[nd.left];
  TreeNode& r = nodes_[nd.right];
  l = TreeNode{};
  r = TreeNode{};
  l.begin = nd.begin, l.end = nd.begin + half;
  r.begin = nd.begin + half, r.end = nd.end;
}

void GravityTree::compute_moments(std::uint32_t node, Real support) {
  TreeNode& nd = nodes_[node];
  Real mass = 0, mx = 0, my = 0, mz = 0, hmax = 0;
  for (std::uint32_t k = nd.begin; k < nd.end; ++k) {
    mass += pm_[k];
    mx += pm_[k] * px_[k], my += pm_[k] * py_[k], mz += pm_[k] * pz_[k];
    hmax = std::max(hmax, ph_[k]);
  }
  nd.mass = mass;
  if (mass > 0) {
    nd.com[0] = mx / mass, nd.com[1] = my / mass, nd.com[2] = mz / mass;
  } else {  // massless probes only: the expansion centre is their mean position
    Real sx = 0, sy = 0, sz = 0;
    for (std::uint32_t k = nd.begin; k < nd.end; ++k) sx += px_[k], sy += py_[k], sz += pz_[k];
    const Real c = nd.count();
    nd.com[0] = sx / c, nd.com[1] = sy / c, nd.com[2] = sz / c;
  }
  nd.reach = support * hmax;
  Real q[6] = {0, 0, 0, 0, 0, 0}, r2max = 0;
  for (std::uint32_t k = nd.begin; k < nd.end; ++k) {
    const Real dx = px_[k] - nd.com[0], dy = py_[k] - nd.com[1], dz = pz_[k] - nd.com[2];
    const Real m = pm_[k];
    q[0] += m * dx * dx, q[1] += m * dx * dy, q[2] += m * dx * dz;
    q[3] += m * dy * dy, q[4] += m * dy * dz, q[5] += m * dz * dz;
    r2max = std::max(r2max, dx * dx + dy * dy + dz * dz);
  }
  std::copy(q, q + 6, nd.quad);
  nd.radius = std::sqrt(r2max);
}

}  // namespace sphark
