// Tree gravity evaluation (see sphark/gravity/tree_gravity.hpp).
#include "sphark/gravity/tree_gravity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <omp.h>
#include <stdexcept>

#include "far_field_sums.hpp"
#include "near_field_sums.hpp"
#include "reuse_buffer.hpp"
#include "sphark/gravity/direct_gravity.hpp"
#include "sphark/gravity/kernel_softening.hpp"
#include "sphark/kernels/kernels.hpp"
#include "gravity_kernels.hpp"

namespace sphark {

namespace {

// Acceleration / G and potential / G accumulated at one particle.
struct FieldSum {
  Real ax = 0, ay = 0, az = 0, pot = 0;
};

}  // namespace

template <class K>
TreeGravity<K>::TreeGravity(const GravityOptions& options) : opt_(options) {
  if (!(opt_.theta > 0 && opt_.theta < 1)) throw std::invalid_argument("tree gravity: theta must be in (0, 1)");
  if (opt_.leaf_size < 1) throw std::invalid_argument("tree gravity: leaf_size must be >= 1");
}

template <class K>
Real TreeGravity<K>::compute(const GravitySources& src, Real* acceleration, Real* potential) {
  tree_.build(src, K::support, opt_.leaf_size);
  mark_targets(src.wanted);
  walk_.walk(tree_, opt_.theta, opt_.opening, targets_.empty() ? nullptr : &targets_);
  bool grew = gravity_detail::resize_reporting_growth(local_, tree_.nodes().size());
  grew |= gravity_detail::resize_reporting_growth(runs_, walk_.near().partner.size());
  grew |= gravity_detail::resize_reporting_growth(newtonian_runs_, tree_.nodes().size());
  grew |= gravity_detail::resize_reporting_growth(all_runs_, tree_.nodes().size());
  if (grew) ++allocations_;
  merge_near_runs();
  far_field_expansions();
  pass_expansions_down();
  const std::vector<std::uint32_t>& leaves = tree_.leaves();
  const auto nl = static_cast<std::ptrdiff_t>(leaves.size());
  if (inside_.size() < static_cast<std::size_t>(omp_get_max_threads())) {
    inside_.resize(static_cast<std::size_t>(omp_get_max_threads()));
    ++allocations_;
  }
  for (auto& buffer : inside_)
    if (gravity_detail::resize_reporting_growth(buffer, masked_length_ + 4)) ++allocations_;
#pragma omp parallel
  {
    std::uint32_t* inside = inside_[static_cast<std::size_t>(omp_get_thread_num())].data();
#pragma omp for schedule(dynamic, 4)
    for (std::ptrdiff_t k = 0; k < nl; ++k) evaluate_leaf(leaves[k], src.wanted, acceleration, potential, inside);
  }
  return src.wanted ? std::numeric_limits<Real>::quiet_NaN() : potential_energy(src.m, potential, src.n);
}

// targets_: per node, whether it holds a wanted particle (children after their parent: bottom up).
template <class K>
void TreeGravity<K>::mark_targets(const std::uint8_t* wanted) {
  targets_.clear();
  if (!wanted) return;
  const std::vector<TreeNode>& nd = tree_.nodes();
  targets_.assign(nd.size(), 0);
  for (std::size_t i = nd.size(); i-- > 0;) {
    if (!nd[i].leaf()) {
      targets_[i] = targets_[nd[i].left] | targets_[nd[i].right];
      continue;
    }
    for (std::uint32_t a = nd[i].begin; a < nd[i].end && !targets_[i]; ++a) targets_[i] = wanted[tree_.order()[a]] != 0;
  }
}

// Step 1: every node's expansion from its far partners, in list order.
template <class K>
void TreeGravity<K>::far_field_expansions() {
  const std::vector<TreeNode>& nd = tree_.nodes();
  const PartnerLists& far = walk_.far();
  const auto nn = static_cast<std::ptrdiff_t>(nd.size());
#pragma omp parallel for schedule(dynamic, 64)
  for (std::ptrdiff_t i = 0; i < nn; ++i) {
    const auto node = static_cast<std::uint32_t>(i);
    if (!target(node)) continue;
    local_[i] = gravity_detail::far_field_of_partners(nd[i], nd, far.partner.data() + far.begin(node),
                                                      far.end(node) - far.begin(node));
  }
}

// Step 2: pre-order (parents first), each node's expansion added to its children's.
template <class K>
void TreeGravity<K>::pass_expansions_down() {
  const std::vector<TreeNode>& nd = tree_.nodes();
  for (std::size_t i = 0; i < nd.size(); ++i) {
    if (nd[i].leaf() || !target(i)) continue;
    for (std::uint32_t c : {nd[i].left, nd[i].right}) {
      const Real d[3] = {nd[c].com[0] - nd[i].com[0], nd[c].com[1] - nd[i].com[1], nd[c].com[2] - nd[i].com[2]};
      add_shifted(local_[c], local_[i], d);
    }
  }
}

// Merges adjacent runs of [first, last) (sorted by begin); returns the new end.
namespace {
template <class Run>
Run* merge_adjacent(Run* first, Run* last) {
  if (first == last) return last;
  Run* out = first;
  for (Run* r = first + 1; r < last; ++r) {
    if (r->begin == out->end)
      out->end = r->end;
    else
      *++out = *r;
  }
  return out + 1;
}
}  // namespace

// Per leaf, in its own slots of runs_: the Newtonian partner leaves' particle ranges merged,
// then the others merged (partner lists are sorted, and leaves in pre-order hold ascending
// particle ranges).
template <class K>
void TreeGravity<K>::merge_near_runs() {
  const std::vector<TreeNode>& nd = tree_.nodes();
  const PartnerLists& near = walk_.near();
  const std::vector<std::uint32_t>& leaves = tree_.leaves();
  const auto nl = static_cast<std::ptrdiff_t>(leaves.size());
  std::uint32_t masked = 0;
#pragma omp parallel for schedule(dynamic, 64) reduction(max : masked)
  for (std::ptrdiff_t j = 0; j < nl; ++j) {
    const std::uint32_t leaf = leaves[j], b0 = near.begin(leaf), b1 = near.end(leaf);
    if (!target(leaf)) {
      newtonian_runs_[leaf] = all_runs_[leaf] = 0;
      continue;
    }
    ParticleRun* first = runs_.data() + b0;
    ParticleRun* newtonian = first;
    for (std::uint32_t k = b0; k < b1; ++k)  // the list is sorted by partner: so are the runs
      if (near.partner[k] & DualTreeWalk::kNewtonian) {
        const TreeNode& B = nd[near.partner[k] & ~DualTreeWalk::kNewtonian];
        *newtonian++ = {B.begin, B.end};
      }
    ParticleRun* newtonian_end = merge_adjacent(first, newtonian);
    ParticleRun* other = newtonian_end;
    for (std::uint32_t k = b0; k < b1; ++k)
      if (!(near.partner[k] & DualTreeWalk::kNewtonian)) *other++ = {nd[near.partner[k]].begin, nd[near.partner[k]].end};
    ParticleRun* all_end = merge_adjacent(newtonian_end, other);
    std::uint32_t length = 0;
    for (const ParticleRun* r = newtonian_end; r < all_end; ++r) length += r->end - r->begin;
    masked = std::max(masked, length);
    newtonian_runs_[leaf] = static_cast<std::uint32_t>(newtonian_end - first);
    all_runs_[leaf] = static_cast<std::uint32_t>(all_end - first);
  }
  masked_length_ = masked;
}

// Step 3: the particles of one leaf, written to their input slots.
template <class K>
void TreeGravity<K>::evaluate_leaf(std::uint32_t leaf, const std::uint8_t* wanted, Real* acceleration,
                                   Real* potential, std::uint32_t* inside) const {
  const TreeNode& A = tree_.nodes()[leaf];
  const PartnerLists& near = walk_.near();
  const Real *x = tree_.x(), *y = tree_.y(), *z = tree_.z(), *m = tree_.m(), *h = tree_.h();
  const gravity_detail::ParticleArrays arrays{x, y, z, m, h, tree_.h_inv()};
  for (std::uint32_t a = A.begin; a < A.end; ++a) {
    const std::uint32_t i = tree_.order()[a];
    if (wanted && !wanted[i]) {  // a source only
      acceleration[3 * i] = acceleration[3 * i + 1] = acceleration[3 * i + 2] = std::numeric_limits<Real>::quiet_NaN();
      potential[i] = std::numeric_limits<Real>::quiet_NaN();
      continue;
    }
    const Real xa[3] = {x[a], y[a], z[a]};
    const Real d[3] = {xa[0] - A.com[0], xa[1] - A.com[1], xa[2] - A.com[2]};
    Real value, grad[3];
    value_and_gradient_at(local_[leaf], d, value, grad);
    FieldSum s{grad[0], grad[1], grad[2], -value + self_potential<K>(m[a], h[a])};
    const ParticleRun* runs = runs_.data() + near.begin(leaf);
    gravity_detail::NewtonianSums newtonian, softened;
    const std::uint32_t n = gravity_detail::add_newtonian_runs(arrays, runs, newtonian_runs_[leaf], all_runs_[leaf], xa,
                                                               K::support * h[a], K::support, a, newtonian, inside);
    gravity_detail::add_softened_list<K>(arrays, inside, n, xa, h[a], arrays.h_inv[a], softened);
    s.ax -= newtonian.fx + softened.fx, s.ay -= newtonian.fy + softened.fy, s.az -= newtonian.fz + softened.fz;
    s.pot += softened.pot - newtonian.pot;
    acceleration[3 * i] = opt_.G * s.ax;
    acceleration[3 * i + 1] = opt_.G * s.ay;
    acceleration[3 * i + 2] = opt_.G * s.az;
    potential[i] = opt_.G * s.pot;
  }
}

#define SPHARK_INSTANTIATE(K) template class TreeGravity<K>;
SPHARK_GRAVITY_KERNELS(SPHARK_INSTANTIATE)
#undef SPHARK_INSTANTIATE

}  // namespace sphark
