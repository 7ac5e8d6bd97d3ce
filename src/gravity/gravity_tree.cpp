// kd-tree build and node moments (see sphark/gravity/gravity_tree.hpp).
#include "sphark/gravity/gravity_tree.hpp"

#include <algorithm>
#include <cmath>
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
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = 0; k < np; ++k)
    points_[k] = {{src.x[3 * k], src.x[3 * k + 1], src.x[3 * k + 2]}, static_cast<std::uint32_t>(k)};
  grew |= resize_reporting_growth(nodes_, n == 0 ? 0 : tree_node_count(n, static_cast<std::uint32_t>(leaf_size)));
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

// Split along the longest side of the bounding box at the left_count-th point (nth_element on
// the node's points, which carry their coordinates: no indirection); the children's slots in
// pre-order.
void GravityTree::split(std::uint32_t node, int leaf_size) {
  TreeNode& nd = nodes_[node];
  const std::uint32_t count = nd.count();
  if (count <= static_cast<std::uint32_t>(leaf_size)) {
    nd.left = nd.right = 0;
    return;
  }
  const auto first = points_.begin() + nd.begin, last = points_.begin() + nd.end;
  Real lo[3], hi[3];
  for (int c = 0; c < 3; ++c) lo[c] = hi[c] = first->x[c];
  for (auto p = first; p != last; ++p)
    for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], p->x[c]), hi[c] = std::max(hi[c], p->x[c]);
  int axis = 0;
  for (int c = 1; c < 3; ++c)
    if (hi[c] - lo[c] > hi[axis] - lo[axis]) axis = c;
  const std::uint32_t half = left_count(count, static_cast<std::uint32_t>(leaf_size));
  std::nth_element(first, first + half, last,
                   [axis](const BuildPoint& a, const BuildPoint& b) { return a.x[axis] < b.x[axis]; });
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
