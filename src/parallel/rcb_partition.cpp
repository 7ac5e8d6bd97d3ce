// partition_rcb: weighted recursive coordinate bisection, every node of a tree level at once
// (see parallel/decomposition.hpp for the method).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "sphark/parallel/decomposition.hpp"

namespace sphark {
namespace {

constexpr int kBins = 32;
constexpr Real kInf = std::numeric_limits<Real>::infinity();

template <int D>
using Node = typename Decomposition<D>::Node;

struct Split {  // one tree node being cut at this level
  int node;     // index into the tree
  int r0, r1;   // its ranks [r0, r1)
  int axis = 0;
  Real a = 0, b = 0;   // current bracket [a, b) of the cut
  Real weight = 0;     // node weight (from the first histogram)
  Real target = 0;     // weight wanted left of the cut
  bool done = false;
  Real cut = 0;
};

// Per split: bounding box of its particles (Allreduce min of lo and of -hi); chooses the
// longest axis and the initial bracket.
template <int D>
void choose_axes(const Communicator& comm, const Real* x, std::size_t n, const std::vector<int>& split_of,
                 std::vector<Split>& splits) {
  std::vector<Real> ext(2 * D * splits.size(), kInf);
  for (std::size_t i = 0; i < n; ++i) {
    if (split_of[i] < 0) continue;
    Real* e = ext.data() + 2 * D * split_of[i];
    for (int k = 0; k < D; ++k) {
      e[k] = std::min(e[k], x[D * i + k]);
      e[D + k] = std::min(e[D + k], -x[D * i + k]);
    }
  }
  comm.allreduce(ext.data(), ext.size(), ReduceOp::Min);
  for (std::size_t s = 0; s < splits.size(); ++s) {
    const Real* e = ext.data() + 2 * D * s;
    int axis = 0;
    for (int k = 1; k < D; ++k)
      if (-e[D + k] - e[k] > -e[D + axis] - e[axis]) axis = k;
    splits[s].axis = axis;
    splits[s].a = e[axis];
    splits[s].b = std::nextafter(-e[D + axis], kInf);  // the largest coordinate lies inside [a, b)
    if (!(splits[s].a < splits[s].b)) splits[s].done = true, splits[s].cut = 0;  // no particles
  }
}

// One refinement: histograms of every unfinished split's bracket (weight below a, then kBins
// weights, then kBins counts), summed over the ranks; shrinks each bracket to the bin where the
// target is crossed, or fixes the cut.
template <int D>
void refine(const Communicator& comm, const Real* x, const Real* w, std::size_t n, const std::vector<int>& split_of,
            std::vector<Split>& splits, bool first, const RcbOptions& opt) {
  constexpr std::size_t stride = 1 + 2 * kBins;
  std::vector<Real> h(stride * splits.size(), 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const int s = split_of[i];
    if (s < 0 || splits[s].done) continue;
    const Split& sp = splits[s];
    const Real xi = x[D * i + sp.axis], wi = w ? w[i] : 1.0;
    Real* hs = h.data() + stride * s;
    if (xi < sp.a) {
      hs[0] += wi;
    } else if (xi < sp.b) {
      const int bin = std::min(kBins - 1, static_cast<int>((xi - sp.a) / ((sp.b - sp.a) / kBins)));
      hs[1 + bin] += wi;
      hs[1 + kBins + bin] += 1;
    }
  }
  comm.allreduce(h.data(), h.size(), ReduceOp::Sum);
  for (std::size_t s = 0; s < splits.size(); ++s) {
    Split& sp = splits[s];
    if (sp.done) continue;
    const Real* hs = h.data() + stride * s;
    if (first) {
      sp.weight = std::accumulate(hs + 1, hs + 1 + kBins, 0.0);
      sp.target = sp.weight * (Real((sp.r1 - sp.r0) / 2) / Real(sp.r1 - sp.r0));
    }
    Real below = hs[0];
    int j = 0;
    while (j < kBins - 1 && below + hs[1 + j] <= sp.target) below += hs[1 + j++];
    const Real width = (sp.b - sp.a) / kBins;
    const Real lo = sp.a + j * width, hi = (j == kBins - 1) ? sp.b : sp.a + (j + 1) * width;
    const bool settled = hs[1 + j] <= opt.tolerance * sp.weight || hs[1 + kBins + j] <= 1 || !(lo < hi) ||
                         hi - lo <= 4 * std::numeric_limits<Real>::epsilon() * std::max(std::abs(lo), std::abs(hi));
    if (settled) {
      sp.done = true;
      sp.cut = (std::abs(below - sp.target) <= std::abs(below + hs[1 + j] - sp.target)) ? lo : hi;
    } else {
      sp.a = lo;
      sp.b = hi;
    }
  }
}

// The splits of one tree level: cuts found, children appended to the tree.
template <int D>
std::vector<Split> next_level(std::vector<Node<D>>& tree, std::vector<Split>& splits, const Real* x, std::size_t n,
                              std::vector<int>& split_of) {
  std::vector<Split> next;
  std::vector<int> child_split(2 * splits.size(), -1);
  for (std::size_t s = 0; s < splits.size(); ++s) {
    const Split& sp = splits[s];
    const int mid = sp.r0 + (sp.r1 - sp.r0) / 2;
    const int ranges[2][2] = {{sp.r0, mid}, {mid, sp.r1}};
    int children[2];
    for (int c = 0; c < 2; ++c) {
      children[c] = static_cast<int>(tree.size());
      Node<D> leaf;
      leaf.rank = ranges[c][0];
      tree.push_back(leaf);
      if (ranges[c][1] - ranges[c][0] >= 2) {
        child_split[2 * s + c] = static_cast<int>(next.size());
        next.push_back(Split{children[c], ranges[c][0], ranges[c][1]});
      }
    }
    Node<D>& parent = tree[sp.node];
    parent.axis = sp.axis;
    parent.cut = sp.cut;
    parent.left = children[0];
    parent.right = children[1];
  }
  for (std::size_t i = 0; i < n; ++i) {
    const int s = split_of[i];
    if (s < 0) continue;
    split_of[i] = child_split[2 * s + (x[D * i + splits[s].axis] < splits[s].cut ? 0 : 1)];
  }
  return next;
}

template <int D>
Real imbalance(const Communicator& comm, const Decomposition<D>& dec, const Real* x, const Real* w, std::size_t n) {
  std::vector<Real> load(comm.size(), 0.0);
  for (std::size_t i = 0; i < n; ++i) load[dec.owner(Eigen::Map<const Vec<D>>(x + D * i))] += w ? w[i] : 1.0;
  comm.allreduce(load.data(), load.size(), ReduceOp::Sum);
  const Real total = std::accumulate(load.begin(), load.end(), 0.0);
  return total > 0 ? *std::max_element(load.begin(), load.end()) * comm.size() / total : 1.0;
}

}  // namespace

template <int D>
Decomposition<D> partition_rcb(const Communicator& comm, const Real* x_in, const Real* weight, std::size_t n,
                               const std::optional<PeriodicBox<D>>& box, const RcbOptions& options, RcbStats* stats) {
  std::vector<Real> wrapped;
  const Real* x = x_in;
  if (box && box->any_periodic()) {
    wrapped.resize(D * n);
    box->wrap_all(x_in, n, wrapped.data());
    x = wrapped.data();
  }
  std::vector<Node<D>> tree(1);
  std::vector<int> split_of(n, comm.size() >= 2 ? 0 : -1);
  std::vector<Split> splits;
  if (comm.size() >= 2) splits.push_back(Split{0, 0, comm.size()});
  int refinements = 0;
  while (!splits.empty()) {
    choose_axes<D>(comm, x, n, split_of, splits);
    for (int it = 0; it < options.max_refinements; ++it) {
      if (std::all_of(splits.begin(), splits.end(), [](const Split& s) { return s.done; })) break;
      refine<D>(comm, x, weight, n, split_of, splits, it == 0, options);
      ++refinements;
    }
    for (Split& sp : splits)
      if (!sp.done) sp.done = true, sp.cut = sp.a;  // max_refinements reached: cut at the bracket
    splits = next_level<D>(tree, splits, x, n, split_of);
  }
  Decomposition<D> dec(box);
  dec.set_tree(std::move(tree));
  if (stats) *stats = RcbStats{refinements, imbalance(comm, dec, x, weight, n)};
  return dec;
}

#define SPHARK_INSTANTIATE_RCB(D)                                                                      \
  template Decomposition<D> partition_rcb<D>(const Communicator&, const Real*, const Real*, std::size_t, \
                                             const std::optional<PeriodicBox<D>>&, const RcbOptions&, RcbStats*);
SPHARK_INSTANTIATE_RCB(1)
SPHARK_INSTANTIATE_RCB(2)
SPHARK_INSTANTIATE_RCB(3)

}  // namespace sphark
