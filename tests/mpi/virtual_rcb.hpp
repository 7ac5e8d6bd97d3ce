#pragma once
// Decompositions of many virtual ranks without MPI (Decomposition::set_tree), and the reference
// query ranks_within is checked and timed against: every domain and every periodic image tested
// (what ranks_within did until session 20). tests/mpi/decomposition_test.cpp, bench/distributed.cpp.
#include <algorithm>
#include <vector>

#include "sphark/parallel/decomposition.hpp"

namespace sphark::testing {

// A balanced RCB tree of P leaves over the box (every rank builds the same; no communication):
// the ranks [r0, r1) split at the fraction (r1 - r0) / 2 / (r1 - r0) of the longest side.
template <int D>
inline int virtual_tree(int r0, int r1, Vec<D> lo, Vec<D> hi, std::vector<typename Decomposition<D>::Node>& nodes) {
  const int me = static_cast<int>(nodes.size());
  nodes.emplace_back();
  if (r1 - r0 == 1) {
    nodes[me].rank = r0;
    return me;
  }
  int axis = 0;
  for (int k = 1; k < D; ++k) axis = hi[k] - lo[k] > hi[axis] - lo[axis] ? k : axis;
  const int k = (r1 - r0) / 2;
  const Real cut = lo[axis] + (hi[axis] - lo[axis]) * Real(k) / Real(r1 - r0);
  Vec<D> left_hi = hi, right_lo = lo;
  left_hi[axis] = cut;
  right_lo[axis] = cut;
  const int left = virtual_tree<D>(r0, r0 + k, lo, left_hi, nodes);
  const int right = virtual_tree<D>(r0 + k, r1, right_lo, hi, nodes);
  nodes[me].axis = axis;
  nodes[me].cut = cut;
  nodes[me].left = left;
  nodes[me].right = right;
  return me;
}

// The reference: every domain and every periodic image tested (what ranks_within did until
// session 20).
template <int D>
inline std::vector<int> every_domain_within(const Decomposition<D>& dec, Vec<D> x, Real r) {
  std::vector<int> out;
  const auto& box = dec.box();
  if (box) x = box->wrap(x);
  int images = 1;
  for (int k = 0; k < D; ++k) images *= (box && box->periodic[k]) ? 3 : 1;
  for (int image = 0; image < images; ++image) {
    Vec<D> p = x;
    for (int k = 0, code = image; k < D; ++k) {
      if (!(box && box->periodic[k])) continue;
      p[k] += (code % 3 - 1) * (box->hi[k] - box->lo[k]);
      code /= 3;
    }
    for (int rank = 0; rank < dec.ranks(); ++rank) {
      const DomainBox<D>& b = dec.domains()[rank];
      Real d2 = 0;
      for (int k = 0; k < D; ++k) {
        const Real d = std::max({b.lo[k] - p[k], p[k] - b.hi[k], Real(0)});
        d2 += d * d;
      }
      if (d2 < r * r) out.push_back(rank);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace sphark::testing
