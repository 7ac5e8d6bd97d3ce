#include "sphark/neighbours/kd_tree_search.hpp"

#include "sphark/neighbours/displacement.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace sphark {

template <int D>
std::size_t KdTreeNeighbourSearch<D>::capacity() const {
  std::size_t c = list_.offsets.capacity() + list_.indices.capacity() + node_.capacity() + index_.capacity() +
                  ppts_.capacity() + pr2_.capacity() + pts_.capacity() + r2_.capacity() + leaves_.capacity() +
                  row_start_.capacity();
  for (const auto& t : thread_rows_) c += t.capacity();
  for (const auto& t : thread_stack_) c += t.capacity();
  return c;
}

// Bounding box of the node's particles; a leaf at <= kLeafSize particles, otherwise the median
// split along the widest axis. Children are appended after their parent, so the reverse node
// order visits children before parents.
template <int D>
void KdTreeNeighbourSearch<D>::split(std::int32_t id) {
  const std::uint32_t b = node_[id].begin, e = node_[id].end;
  const Real* p = ppts_.data();
  Vec<D> lo = Vec<D>::Constant(std::numeric_limits<Real>::infinity()), hi = -lo;
  for (std::uint32_t s = b; s < e; ++s) {
    const Eigen::Map<const Vec<D>> q(p + D * index_[s]);
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  node_[id].lo = lo;
  node_[id].hi = hi;
  if (e - b <= kLeafSize) return;
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const std::uint32_t mid = b + (e - b) / 2;
  std::nth_element(index_.begin() + b, index_.begin() + mid, index_.begin() + e,
                   [p, axis](std::uint32_t u, std::uint32_t v) { return p[D * u + axis] < p[D * v + axis]; });
  const auto left = static_cast<std::int32_t>(node_.size());
  node_.push_back(Node{lo, hi, 0, b, mid, -1, -1});
  node_.push_back(Node{lo, hi, 0, mid, e, -1, -1});
  node_[id].left = left;
  node_[id].right = left + 1;
  split(left);
  split(left + 1);
}

template <int D>
void KdTreeNeighbourSearch<D>::build_tree(std::size_t n) {
  index_.resize(n);
  std::iota(index_.begin(), index_.end(), 0u);
  node_.clear();
  node_.push_back(Node{Vec<D>::Zero(), Vec<D>::Zero(), 0, 0, static_cast<std::uint32_t>(n), -1, -1});
  if (n > 0) split(0);
  pts_.resize(D * n);
  r2_.resize(n);
  for (std::size_t s = 0; s < n; ++s) {
    const std::uint32_t a = index_[s];
    for (int k = 0; k < D; ++k) pts_[D * s + k] = ppts_[D * a + k];
    r2_[s] = pr2_[a];
  }
  leaves_.clear();
  for (std::size_t id = 0; id < node_.size(); ++id)
    if (node_[id].left < 0) leaves_.push_back(static_cast<std::int32_t>(id));
  std::sort(leaves_.begin(), leaves_.end(), [this](std::int32_t a, std::int32_t b) { return node_[a].begin < node_[b].begin; });
  for (std::size_t id = node_.size(); id-- > 0;) {
    Node& nd = node_[id];
    nd.reach2 = 0;
    if (nd.left < 0)
      for (std::uint32_t s = nd.begin; s < nd.end; ++s) nd.reach2 = std::max(nd.reach2, r2_[s]);
    else
      nd.reach2 = std::max(node_[nd.left].reach2, node_[nd.right].reach2);
  }
}

// Gap between [alo, ahi] and [blo, bhi] along axis k (0 if they overlap); along a periodic axis
// of length L the shorter way round: arcs of lengths la, lb a gap g apart one way are
// L - la - lb - g apart the other way.
template <int D>
Real KdTreeNeighbourSearch<D>::gap(Real alo, Real ahi, Real blo, Real bhi, int k) const {
  Real g = std::max<Real>(0, std::max(blo - ahi, alo - bhi));
  if (period_[k] > 0 && g > 0) g = std::max<Real>(0, std::min(g, period_[k] - (ahi - alo) - (bhi - blo) - g));
  return g;
}

template <int D>
Real KdTreeNeighbourSearch<D>::box_distance2(const Node& nd, const Real* p) const {
  Real d2 = 0;
  for (int k = 0; k < D; ++k) {
    const Real g = gap(p[k], p[k], nd.lo[k], nd.hi[k], k);
    d2 += g * g;
  }
  return d2;
}

template <int D>
Real KdTreeNeighbourSearch<D>::box_distance2(const Node& a, const Node& b) const {
  Real d2 = 0;
  for (int k = 0; k < D; ++k) {
    const Real g = gap(a.lo[k], a.hi[k], b.lo[k], b.hi[k], k);
    d2 += g * g;
  }
  return d2;
}

// Built particles within sqrt(r2) of p (a query, not the lists).
template <int D>
void KdTreeNeighbourSearch<D>::collect(const Real* p, Real r2, std::vector<std::uint32_t>& out,
                                       std::vector<std::int32_t>& stack) const {
  const MinimumImage<D> image(box_);
  stack.assign(1, 0);
  while (!stack.empty()) {
    const Node& nd = node_[stack.back()];
    stack.pop_back();
    if (box_distance2(nd, p) >= r2) continue;
    if (nd.left >= 0) {
      stack.push_back(nd.right);
      stack.push_back(nd.left);
      continue;
    }
    for (std::uint32_t s = nd.begin; s < nd.end; ++s)
      if (image(p, pts_.data() + D * s).squaredNorm() < r2) out.push_back(index_[s]);
  }
}

// The leaves that may hold a neighbour of some particle of leaf `a`: a node is opened when its
// box lies within max(r_a, r_node) of a's box (r_a, r_node: the largest radius in each).
template <int D>
void KdTreeNeighbourSearch<D>::candidate_leaves(const Node& a, std::vector<std::int32_t>& out,
                                                std::vector<std::int32_t>& stack) const {
  out.clear();
  stack.assign(1, 0);
  while (!stack.empty()) {
    const std::int32_t id = stack.back();
    stack.pop_back();
    const Node& nd = node_[id];
    if (box_distance2(a, nd) >= std::max(a.reach2, nd.reach2)) continue;
    if (nd.left >= 0) {
      stack.push_back(nd.right);
      stack.push_back(nd.left);
    } else {
      out.push_back(id);
    }
  }
}

// Leaf by leaf (one traversal per leaf, shared by its particles), contiguous slot ranges per
// thread; each thread then copies its rows to their places in particle order.
template <int D>
void KdTreeNeighbourSearch<D>::list_rows(const std::uint32_t* key) {
  const std::size_t n = n_;
  const int max_threads = omp_get_max_threads();
  if (thread_rows_.size() < static_cast<std::size_t>(max_threads)) thread_rows_.resize(max_threads);
  if (thread_stack_.size() < static_cast<std::size_t>(2 * max_threads)) thread_stack_.resize(2 * max_threads);
  list_.offsets.assign(n + 1, 0);
  row_start_.resize(n);
  const MinimumImage<D> image(box_);
#pragma omp parallel
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    // this thread's leaves: those starting in its share of the slots
    auto leaf_at = [&](std::size_t slot) {
      return std::lower_bound(leaves_.begin(), leaves_.end(), slot,
                              [this](std::int32_t l, std::size_t v) { return node_[l].begin < v; });
    };
    const auto lf = leaf_at(n * t / nt), ll = leaf_at(n * (t + 1) / nt);
    // this thread's rows: out[0, used) (out only grows: no clearing and refilling per build)
    std::vector<std::uint32_t>& out = thread_rows_[t];
    std::vector<std::int32_t>&cand = thread_stack_[2 * t], &stack = thread_stack_[2 * t + 1];
    std::size_t used = 0;
    for (auto leaf = lf; leaf != ll; ++leaf) {
      const Node& a = node_[*leaf];
      candidate_leaves(a, cand, stack);
      for (std::uint32_t s = a.begin; s < a.end; ++s) {
        const std::uint32_t i = index_[s];
        const Real* p = pts_.data() + D * s;
        const Real r2 = r2_[s];
        row_start_[s] = used;
        for (std::int32_t b : cand) {
          const Node& nb = node_[b];
          // a leaf none of whose particles can be within max(r_i, r_j) of this one (the leaf
          // traversal opened it for the largest radius of i's leaf)
          if (box_distance2(nb, p) >= std::max(r2, nb.reach2)) continue;
          if (out.size() < used + (nb.end - nb.begin)) out.resize(2 * (used + (nb.end - nb.begin)));
          std::size_t pos = used;
          for (std::uint32_t u = nb.begin; u < nb.end; ++u) {  // branch-free append, as the cell grid
            const Real d2 = image(p, pts_.data() + D * u).squaredNorm();
            out[pos] = index_[u];
            pos += (d2 < std::max(r2, r2_[u])) & (u != s);
          }
          used = pos;
        }
        const auto row = out.begin() + static_cast<std::ptrdiff_t>(row_start_[s]), end = out.begin() + static_cast<std::ptrdiff_t>(used);
        if (key)
          std::sort(row, end, [key](std::uint32_t x, std::uint32_t y) { return key[x] < key[y]; });
        else
          std::sort(row, end);
        list_.offsets[i + 1] = used - row_start_[s];
      }
    }
#pragma omp barrier
#pragma omp single
    {
      for (std::size_t i = 0; i < n; ++i) list_.offsets[i + 1] += list_.offsets[i];
      const std::size_t pairs = list_.offsets[n];
      if (pairs > list_.indices.capacity()) list_.indices.reserve(pairs + pairs / 8);
      list_.indices.resize(pairs);
    }
    for (auto leaf = lf; leaf != ll; ++leaf)
      for (std::uint32_t s = node_[*leaf].begin; s < node_[*leaf].end; ++s) {
        const std::uint32_t i = index_[s];
        const std::size_t count = list_.offsets[i + 1] - list_.offsets[i];
        std::copy(out.begin() + row_start_[s], out.begin() + row_start_[s] + count,
                  list_.indices.begin() + list_.offsets[i]);
      }
  }
}

template <int D>
void KdTreeNeighbourSearch<D>::build(const Real* x, std::size_t n, Real radius, const std::uint32_t* key,
                                     const Real* radii) {
  if (!(radius > 0)) throw std::invalid_argument("KdTreeNeighbourSearch::build: radius must be positive");
  if (n >= (std::size_t{1} << 31)) throw std::invalid_argument("KdTreeNeighbourSearch::build: too many particles");
  if (box_)
    for (int k = 0; k < D; ++k)
      if (box_->periodic[k] && box_->hi[k] - box_->lo[k] < 2 * radius)
        throw std::invalid_argument("KdTreeNeighbourSearch: periodic box length along axis " + std::to_string(k) +
                                    " is shorter than twice the search radius " + std::to_string(radius));
  const std::size_t before = capacity();
  for (int k = 0; k < D; ++k) period_[k] = box_ && box_->periodic[k] ? box_->hi[k] - box_->lo[k] : 0;
  radius_ = radius;
  n_ = n;
  ppts_.resize(D * n);
  pr2_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<D> xi = Eigen::Map<const Vec<D>>(x + D * i);
    Eigen::Map<Vec<D>>(ppts_.data() + D * i) = box_ ? box_->wrap(xi) : xi;
    const Real r = radii ? std::min(radii[i], radius) : radius;
    pr2_[i] = r * r;
  }
  build_tree(n);
  list_rows(key);
  if (capacity() != before) ++allocations_;
}

template <int D>
void KdTreeNeighbourSearch<D>::renumber(const std::vector<std::uint32_t>& order) {
  const std::size_t n = n_;
  if (order.size() != n) throw std::invalid_argument("KdTreeNeighbourSearch::renumber: one entry per particle");
  std::vector<std::uint32_t>& inverse = scratch_u32_;
  inverse.resize(n);
  for (std::size_t i = 0; i < n; ++i) inverse[order[i]] = static_cast<std::uint32_t>(i);
  scratch_offsets_.resize(n + 1);
  scratch_offsets_[0] = 0;
  for (std::size_t i = 0; i < n; ++i) scratch_offsets_[i + 1] = scratch_offsets_[i] + list_.count(order[i]);
  swap_rows_.resize(list_.indices.size());
  swap_pts_.resize(ppts_.size());
  swap_r2_.resize(n);
  spans_.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t o = order[i];
    spans_[i] = renumber_row(list_, o, inverse.data(), static_cast<std::uint32_t>(i), &swap_rows_[scratch_offsets_[i]]);
    for (int k = 0; k < D; ++k) swap_pts_[D * i + k] = ppts_[D * o + k];
    swap_r2_[i] = pr2_[o];
  }
  std::copy(swap_rows_.begin(), swap_rows_.end(), list_.indices.begin());
  std::copy(scratch_offsets_.begin(), scratch_offsets_.end(), list_.offsets.begin());
  std::copy(swap_pts_.begin(), swap_pts_.end(), ppts_.begin());
  std::copy(swap_r2_.begin(), swap_r2_.end(), pr2_.begin());
  for (auto& a : index_) a = inverse[a];
}

template <int D>
void KdTreeNeighbourSearch<D>::keep(const std::vector<std::uint32_t>& kept) {
  std::vector<std::uint32_t>& inverse = scratch_u32_;
  keep_rows(list_, kept, spans_, inverse);
  for (std::size_t i = 0; i < kept.size(); ++i) {
    for (int k = 0; k < D; ++k) ppts_[D * i + k] = ppts_[D * kept[i] + k];
    pr2_[i] = pr2_[kept[i]];
  }
  ppts_.resize(D * kept.size());
  pr2_.resize(kept.size());
  std::size_t w = 0;  // the tree order, renamed (its nodes dropped)
  for (std::uint32_t a : index_)
    if (inverse[a] != kGoneParticle) index_[w++] = inverse[a];
  index_.resize(w);
  node_.clear();
  leaves_.clear();
  n_ = kept.size();
}

template <int D>
void KdTreeNeighbourSearch<D>::query(const Vec<D>& p, Real radius, std::vector<std::uint32_t>& out) const {
  out.clear();
  if (list_.offsets.empty()) throw std::logic_error("KdTreeNeighbourSearch::query before build");
  if (node_.empty() && n_ > 0) throw std::logic_error("KdTreeNeighbourSearch::query after keep(): build again");
  if (box_ && radius > radius_)
    throw std::invalid_argument("KdTreeNeighbourSearch::query: periodic query radius exceeds the build radius");
  if (n_ == 0) return;
  const Vec<D> q = box_ ? box_->wrap(p) : p;
  std::vector<std::int32_t> stack;
  collect(q.data(), radius * radius, out, stack);
  std::sort(out.begin(), out.end());
}

template <int D>
Real KdTreeNeighbourSearch<D>::max_displacement_since_build(const Real* x) const {
  return max_displacement<D>(x, ppts_.data(), n_, box_);
}

template <int D>
void KdTreeNeighbourSearch<D>::displacements_since_build(const Real* x, std::vector<Real>& out) const {
  displacements<D>(x, ppts_.data(), n_, box_, out);
}

template class KdTreeNeighbourSearch<1>;
template class KdTreeNeighbourSearch<2>;
template class KdTreeNeighbourSearch<3>;

}  // namespace sphark
