// The RCB tree (owner lookup, ranks near a point) and its domains. partition_rcb: rcb_partition.cpp.
#include "sphark/parallel/decomposition.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace sphark {
namespace {

constexpr Real kInf = std::numeric_limits<Real>::infinity();

template <int D>
DomainBox<D> root_box(const std::optional<PeriodicBox<D>>& box) {
  DomainBox<D> b{Vec<D>::Constant(-kInf), Vec<D>::Constant(kInf)};
  if (box)
    for (int k = 0; k < D; ++k)
      if (box->periodic[k]) b.lo[k] = box->lo[k], b.hi[k] = box->hi[k];
  return b;
}

template <int D>
Real distance2(const Vec<D>& p, const Vec<D>& lo, const Vec<D>& hi) {
  Real d2 = 0;
  for (int k = 0; k < D; ++k) {
    const Real d = std::max({lo[k] - p[k], p[k] - hi[k], Real(0)});
    d2 += d * d;
  }
  return d2;
}

}  // namespace

template <int D>
Decomposition<D>::Decomposition(std::optional<PeriodicBox<D>> box) : box_(std::move(box)) {
  nodes_.push_back(Node{});
  domains_.push_back(root_box(box_));
}

template <int D>
void Decomposition<D>::set_tree(std::vector<Node> nodes) {
  if (nodes.empty()) throw std::invalid_argument("Decomposition: empty tree");
  std::vector<DomainBox<D>> domains;
  std::vector<int> seen;
  struct Item { int node; DomainBox<D> b; };
  std::vector<Item> stack{{0, root_box(box_)}};
  while (!stack.empty()) {
    const Item it = stack.back();
    stack.pop_back();
    if (it.node < 0 || it.node >= static_cast<int>(nodes.size())) throw std::invalid_argument("Decomposition: bad node index");
    const Node& n = nodes[it.node];
    if (n.axis < 0) {
      if (n.rank < 0) throw std::invalid_argument("Decomposition: leaf without a rank");
      if (static_cast<int>(domains.size()) <= n.rank) domains.resize(n.rank + 1, DomainBox<D>{Vec<D>::Zero(), Vec<D>::Zero()});
      domains[n.rank] = it.b;
      seen.push_back(n.rank);
      continue;
    }
    if (n.axis >= D) throw std::invalid_argument("Decomposition: bad axis");
    DomainBox<D> left = it.b, right = it.b;
    left.hi[n.axis] = n.cut;
    right.lo[n.axis] = n.cut;
    stack.push_back({n.right, right});
    stack.push_back({n.left, left});
  }
  std::sort(seen.begin(), seen.end());
  for (std::size_t r = 0; r < seen.size(); ++r)
    if (seen[r] != static_cast<int>(r)) throw std::invalid_argument("Decomposition: ranks are not 0..P-1, each once");
  nodes_ = std::move(nodes);
  domains_ = std::move(domains);
}

template <int D>
int Decomposition<D>::owner(const Vec<D>& x) const {
  const Vec<D> p = wrapped(x);
  int node = 0;
  while (nodes_[node].axis >= 0) node = p[nodes_[node].axis] < nodes_[node].cut ? nodes_[node].left : nodes_[node].right;
  return nodes_[node].rank;
}

template <int D>
void Decomposition<D>::owners(const Real* x, std::size_t n, int* out) const {
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) out[i] = owner(Eigen::Map<const Vec<D>>(x + D * i));
}

// Down the tree of cuts: a child is visited only if the ball (p, r) reaches its half-space (the
// distance to x[axis] < cut is max(0, p[axis] - cut), to x[axis] >= cut max(0, cut - p[axis]));
// a leaf's domain is then tested exactly. O(log P + leaves near p) instead of O(P).
template <int D>
void Decomposition<D>::ranks_near(int node, const Vec<D>& p, Real r, std::vector<int>& out) const {
  const Node& n = nodes_[node];
  if (n.axis < 0) {
    const DomainBox<D>& b = domains_[n.rank];
    if (distance2(p, b.lo, b.hi) < r * r) out.push_back(n.rank);
    return;
  }
  if (p[n.axis] - n.cut < r) ranks_near(n.left, p, r, out);
  if (n.cut - p[n.axis] < r) ranks_near(n.right, p, r, out);
}

// Along a periodic axis the images p + s L (s = -1, 0, 1) that come within r of the box.
template <int D>
void Decomposition<D>::ranks_within(const Vec<D>& x, Real r, std::vector<int>& out) const {
  const std::size_t first = out.size();
  const Vec<D> p0 = wrapped(x);
  int images = 1;
  for (int k = 0; k < D; ++k) images *= (box_ && box_->periodic[k]) ? 3 : 1;
  for (int image = 0; image < images; ++image) {
    Vec<D> p = p0;
    bool reaches = true;
    for (int k = 0, code = image; k < D; ++k) {
      if (!(box_ && box_->periodic[k])) continue;
      p[k] += (code % 3 - 1) * (box_->hi[k] - box_->lo[k]);  // shifts -L, 0, +L
      code /= 3;
      reaches = reaches && p[k] > box_->lo[k] - r && p[k] < box_->hi[k] + r;
    }
    if (reaches) ranks_near(0, p, r, out);
  }
  std::sort(out.begin() + first, out.end());
  out.erase(std::unique(out.begin() + first, out.end()), out.end());
}

template class Decomposition<1>;
template class Decomposition<2>;
template class Decomposition<3>;

}  // namespace sphark
