// The mutual walk (see sphark/gravity/dual_tree_walk.hpp).
#include "sphark/gravity/dual_tree_walk.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sphark {

namespace {
using WalkNode = DualTreeWalk::WalkNode;
// |z_A - z_B|^2, computed identically for (A, B) and (B, A).
Real centre_distance2(const WalkNode& A, const WalkNode& B) {
  const Real dx = A.com[0] - B.com[0], dy = A.com[1] - B.com[1], dz = A.com[2] - B.com[2];
  return dx * dx + dy * dy + dz * dz;
}
// No particle of one node can be inside the softening reach of a particle of the other:
// |z_A - z_B| >= r_A + r_B + max(reach_A, reach_B).
bool beyond_softening(const WalkNode& A, const WalkNode& B, Real d2) {
  const Real gap = A.radius + B.radius + std::max(A.reach, B.reach);
  return d2 >= gap * gap;
}
}  // namespace

// The mass-dependent opening angle (self_gravity.hpp): g(theta) = theta^5 - c (1 - theta)^2 rises
// from -c at 0 to 1 at 1, and g(theta_0) <= 0 for c >= c_0; Newton steps kept inside the bracket
// [lo, hi] (bisection where a step leaves it) to the bracket's round-off.
Real mass_opening_angle(Real theta_0, Real mass_ratio) {
  const Real c = std::pow(theta_0, 5) / ((1 - theta_0) * (1 - theta_0)) * std::cbrt(std::max(mass_ratio, Real(1)));
  Real lo = theta_0, hi = 1, t = theta_0;
  for (int i = 0; i < 60 && hi - lo > 1e-14; ++i) {
    const Real t2 = t * t, g = t2 * t2 * t - c * (1 - t) * (1 - t);
    if (g == 0) return t;
    (g < 0 ? lo : hi) = t;
    const Real step = g / (5 * t2 * t2 + 2 * c * (1 - t));
    t = (t - step > lo && t - step < hi) ? t - step : (lo + hi) / 2;
  }
  return t;
}

Real DualTreeWalk::opening_angle(OpeningMemo& memo, Real theta_0, Real root_mass, Real mass) {
  if (memo.mass != mass || memo.root_mass != root_mass || memo.theta_0 != theta_0)
    memo = {mass, root_mass, theta_0, mass_opening_angle(theta_0, root_mass / mass)};
  return memo.theta_c;
}

DualTreeWalk::Step DualTreeWalk::classify(std::uint32_t a, std::uint32_t b) const {
  const WalkNode &A = nodes_[a], &B = nodes_[b];
  if (a == b) return A.leaf() ? Step::Near : Step::Self;
  const Real d2 = centre_distance2(A, B), open = A.critical + B.critical;
  if (open * open < d2 && beyond_softening(A, B, d2)) return Step::Far;
  if (A.leaf() && B.leaf()) return Step::Near;
  if (B.leaf() || (!A.leaf() && A.radius >= B.radius)) return Step::SplitA;
  return Step::SplitB;
}

// Every pair of leaves under a and b (a == b: the pairs within a, each once) into out.near.
void DualTreeWalk::record_leaf_pairs(std::uint32_t a, std::uint32_t b, Found& out) const {
  const WalkNode &A = nodes_[a], &B = nodes_[b];
  if (a == b && !A.leaf()) {
    record_leaf_pairs(A.left, A.left, out);
    record_leaf_pairs(A.right, A.right, out);
    record_leaf_pairs(A.left, A.right, out);
  } else if (!A.leaf()) {
    record_leaf_pairs(A.left, b, out);
    record_leaf_pairs(A.right, b, out);
  } else if (!B.leaf()) {
    record_leaf_pairs(a, B.left, out);
    record_leaf_pairs(a, B.right, out);
  } else {
    const bool newtonian = a != b && beyond_softening(A, B, centre_distance2(A, B));
    out.near.push_back({a, newtonian ? (b | kNewtonian) : b});
  }
}

// Terminal steps into out; splits are the caller's (depth or breadth first).
void DualTreeWalk::record(Step s, NodePair p, Found& out) const {
  if (s == Step::Far) out.far.push_back(p);
  if (s == Step::Near) record_leaf_pairs(p.a, p.b, out);
}

void DualTreeWalk::walk_depth_first(NodePair p, Found& out) const {
  if (!wanted(p)) return;  // (nor any pair below it)
  const Step s = classify(p.a, p.b);
  const WalkNode &A = nodes_[p.a], &B = nodes_[p.b];
  switch (s) {
    case Step::Far:
    case Step::Near:
      record(s, p, out);
      return;
    case Step::Self:
      walk_depth_first({A.left, A.left}, out);
      walk_depth_first({A.right, A.right}, out);
      walk_depth_first({A.left, A.right}, out);
      return;
    case Step::SplitA:
      walk_depth_first({A.left, p.b}, out);
      walk_depth_first({A.right, p.b}, out);
      return;
    case Step::SplitB:
      walk_depth_first({p.a, B.left}, out);
      walk_depth_first({p.a, B.right}, out);
      return;
  }
}

// Expands (root, root) breadth first until kJobs pairs wait (or nothing is left to split);
// the waiting pairs stay in queue_ from index head on, moved to the front.
void DualTreeWalk::expand_breadth_first(Found& out) {
  queue_.assign(1, NodePair{0, 0});
  std::size_t head = 0;
  while (head < queue_.size() && queue_.size() - head < static_cast<std::size_t>(kJobs)) {
    const NodePair p = queue_[head++];
    const Step s = classify(p.a, p.b);
    const WalkNode &A = nodes_[p.a], &B = nodes_[p.b];
    if (s == Step::Far || s == Step::Near) {
      if (wanted(p)) record(s, p, out);
    } else if (s == Step::Self) {
      queue_.push_back({A.left, A.left});
      queue_.push_back({A.right, A.right});
      queue_.push_back({A.left, A.right});
    } else if (s == Step::SplitA) {
      queue_.push_back({A.left, p.b});
      queue_.push_back({A.right, p.b});
    } else {
      queue_.push_back({p.a, B.left});
      queue_.push_back({p.a, B.right});
    }
  }
  queue_.erase(queue_.begin(), queue_.begin() + static_cast<std::ptrdiff_t>(head));
}

std::size_t DualTreeWalk::capacity() const {
  std::size_t c = queue_.capacity() + found_.capacity() + cursor_.capacity() + nodes_.capacity() + memo_.capacity();
  for (const Found& f : found_) c += f.far.capacity() + f.near.capacity();
  for (const PartnerLists* l : {&far_, &near_}) c += l->start.capacity() + l->partner.capacity();
  return c;
}

void DualTreeWalk::walk(const GravityTree& tree, Real theta, GravityOpening opening,
                        const std::vector<std::uint8_t>* targets) {
  if (!(theta > 0 && theta < 1)) throw std::invalid_argument("DualTreeWalk: theta must be in (0, 1)");
  if (targets && targets->size() != tree.nodes().size()) throw std::invalid_argument("DualTreeWalk: one target flag per node");
  targets_ = targets;
  const std::size_t capacity_before = capacity();
  const std::vector<TreeNode>& tn = tree.nodes();
  nodes_.resize(tn.size());
  memo_.resize(tn.size());
  const auto nn = static_cast<std::ptrdiff_t>(tn.size());
  const Real root_mass = tn.empty() ? 0 : tn[0].mass;
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < nn; ++i) {
    const TreeNode& t = tn[i];
    const Real theta_c = opening == GravityOpening::Fixed || !(t.mass > 0) ? theta
                                                                          : opening_angle(memo_[i], theta, root_mass, t.mass);
    nodes_[i] = {{t.com[0], t.com[1], t.com[2]}, t.radius, t.reach, t.radius / theta_c, t.count(), t.left, t.right};
  }
  if (found_.empty()) found_.resize(1 + kJobs);
  for (Found& f : found_) f.far.clear(), f.near.clear();
  queue_.clear();
  if (!nodes_.empty()) expand_breadth_first(found_[0]);
  // The expansion stops at kJobs or more waiting pairs: up to kJobs + 1 (a Self step takes one
  // and adds three), so the job slots follow the queue.
  if (found_.size() < 1 + queue_.size()) found_.resize(1 + queue_.size());
  const auto jobs = static_cast<std::ptrdiff_t>(queue_.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::ptrdiff_t j = 0; j < jobs; ++j) walk_depth_first(queue_[j], found_[1 + j]);
  far_pairs_ = assemble(far_, &Found::far, ~0u, false);
  near_pairs_ = assemble(near_, &Found::near, ~kNewtonian, true);
  targets_ = nullptr;
  if (capacity() > capacity_before) ++allocations_;
}

// Per-node partner lists from the unordered pairs (in the order found: prologue, then jobs),
// then, if sorted, each list sorted by partner (OpenMP over nodes). index_mask strips the flag
// bits from an entry. Returns the number of unordered pairs.
std::size_t DualTreeWalk::assemble(PartnerLists& lists, std::vector<NodePair> Found::*which, std::uint32_t index_mask,
                                   bool sorted) {
  const std::size_t nn = nodes_.size();
  lists.start.assign(nn + 1, 0);
  std::size_t pairs = 0;
  for (const Found& f : found_)
    for (const NodePair& p : f.*which) {
      ++lists.start[p.a + 1];
      if (p.a != (p.b & index_mask)) ++lists.start[(p.b & index_mask) + 1];
      ++pairs;
    }
  for (std::size_t i = 0; i < nn; ++i) lists.start[i + 1] += lists.start[i];
  lists.partner.resize(lists.start[nn]);
  cursor_.assign(lists.start.begin(), lists.start.end() - 1);
  for (const Found& f : found_)
    for (const NodePair& p : f.*which) {
      const std::uint32_t b = p.b & index_mask, flag = p.b & ~index_mask;
      lists.partner[cursor_[p.a]++] = p.b;
      if (p.a != b) lists.partner[cursor_[b]++] = p.a | flag;
    }
  if (!sorted) return pairs;
  const auto n = static_cast<std::ptrdiff_t>(nn);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::ptrdiff_t i = 0; i < n; ++i)
    std::sort(lists.partner.begin() + lists.start[i], lists.partner.begin() + lists.start[i + 1],
              [index_mask](std::uint32_t x, std::uint32_t y) { return (x & index_mask) < (y & index_mask); });
  return pairs;
}

}  // namespace sphark
