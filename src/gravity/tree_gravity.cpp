// Tree gravity evaluation (see sphark/gravity/tree_gravity.hpp).
#include "sphark/gravity/tree_gravity.hpp"

#include <cmath>
#include <stdexcept>

#include "reuse_buffer.hpp"
#include "sphark/gravity/direct_gravity.hpp"
#include "sphark/gravity/kernel_softening.hpp"
#include "sphark/kernels/kernels.hpp"

namespace sphark {

namespace {

// Acceleration / G and potential / G accumulated at one particle.
struct FieldSum {
  Real ax = 0, ay = 0, az = 0, pot = 0;
};

// Particles [b0, b1) of a leaf none of whose pairs with a's leaf is inside a softening.
void add_newtonian(const GravityTree& t, std::uint32_t b0, std::uint32_t b1, const Real xa[3], FieldSum& s) {
  const Real *x = t.x(), *y = t.y(), *z = t.z(), *m = t.m();
  Real fx = 0, fy = 0, fz = 0, pot = 0;
#pragma omp simd reduction(+ : fx, fy, fz, pot)
  for (std::uint32_t b = b0; b < b1; ++b) {
    const Real dx = xa[0] - x[b], dy = xa[1] - y[b], dz = xa[2] - z[b];
    const Real inv_r = 1 / std::sqrt(dx * dx + dy * dy + dz * dz);
    const Real m_r = m[b] * inv_r, c = m_r * inv_r * inv_r;
    fx += c * dx, fy += c * dy, fz += c * dz;
    pot += m_r;
  }
  s.ax -= fx, s.ay -= fy, s.az -= fz, s.pot -= pot;
}

// Particles [b0, b1) (skipping slot `self`) with the softened pair interaction.
template <class K>
void add_softened(const GravityTree& t, std::uint32_t b0, std::uint32_t b1, std::uint32_t self, const Real xa[3],
                  Real ha, FieldSum& s) {
  const Real *x = t.x(), *y = t.y(), *z = t.z(), *m = t.m(), *h = t.h();
  for (std::uint32_t b = b0; b < b1; ++b) {
    if (b == self) continue;
    const Real dx = xa[0] - x[b], dy = xa[1] - y[b], dz = xa[2] - z[b];
    const PairGravity p = softened_pair<K>(dx * dx + dy * dy + dz * dz, ha, h[b]);
    const Real c = m[b] * p.force_over_r;
    s.ax -= c * dx, s.ay -= c * dy, s.az -= c * dz;
    s.pot += m[b] * p.phi;
  }
}

}  // namespace

template <class K>
TreeGravity<K>::TreeGravity(const GravityOptions& options) : opt_(options) {
  if (!(opt_.theta > 0 && opt_.theta < 1)) throw std::invalid_argument("tree gravity: theta must be in (0, 1)");
  if (opt_.leaf_size < 1) throw std::invalid_argument("tree gravity: leaf_size must be >= 1");
}

template <class K>
Real TreeGravity<K>::compute(const GravitySources& src, Real* acceleration, Real* potential) {
  tree_.build(src, K::support, opt_.leaf_size);
  walk_.walk(tree_, opt_.theta);
  if (gravity_detail::resize_reporting_growth(local_, tree_.nodes().size())) ++allocations_;
  far_field_expansions();
  pass_expansions_down();
  const std::vector<std::uint32_t>& leaves = tree_.leaves();
  const auto nl = static_cast<std::ptrdiff_t>(leaves.size());
#pragma omp parallel for schedule(dynamic, 4)
  for (std::ptrdiff_t k = 0; k < nl; ++k) evaluate_leaf(leaves[k], acceleration, potential);
  return potential_energy(src.m, potential, src.n);
}

// Step 1: every node's expansion from its far partners, in list order.
template <class K>
void TreeGravity<K>::far_field_expansions() {
  const std::vector<TreeNode>& nd = tree_.nodes();
  const PartnerLists& far = walk_.far();
  const auto nn = static_cast<std::ptrdiff_t>(nd.size());
#pragma omp parallel for schedule(dynamic, 64)
  for (std::ptrdiff_t i = 0; i < nn; ++i) {
    LocalExpansion L;
    const TreeNode& A = nd[i];
    for (std::uint32_t k = far.begin(static_cast<std::uint32_t>(i)); k < far.end(static_cast<std::uint32_t>(i)); ++k) {
      const TreeNode& B = nd[far.partner[k]];
      const Real R[3] = {A.com[0] - B.com[0], A.com[1] - B.com[1], A.com[2] - B.com[2]};
      add_far_field(L, R, B.mass, B.quad);
    }
    local_[i] = L;
  }
}

// Step 2: pre-order (parents first), each node's expansion added to its children's.
template <class K>
void TreeGravity<K>::pass_expansions_down() {
  const std::vector<TreeNode>& nd = tree_.nodes();
  for (std::size_t i = 0; i < nd.size(); ++i) {
    if (nd[i].leaf()) continue;
    for (std::uint32_t c : {nd[i].left, nd[i].right}) {
      const Real d[3] = {nd[c].com[0] - nd[i].com[0], nd[c].com[1] - nd[i].com[1], nd[c].com[2] - nd[i].com[2]};
      add_shifted(local_[c], local_[i], d);
    }
  }
}

// Step 3: the particles of one leaf, written to their input slots.
template <class K>
void TreeGravity<K>::evaluate_leaf(std::uint32_t leaf, Real* acceleration, Real* potential) const {
  const TreeNode& A = tree_.nodes()[leaf];
  const PartnerLists& near = walk_.near();
  const Real *x = tree_.x(), *y = tree_.y(), *z = tree_.z(), *m = tree_.m(), *h = tree_.h();
  for (std::uint32_t a = A.begin; a < A.end; ++a) {
    const Real xa[3] = {x[a], y[a], z[a]};
    const Real d[3] = {xa[0] - A.com[0], xa[1] - A.com[1], xa[2] - A.com[2]};
    Real value, grad[3];
    value_and_gradient_at(local_[leaf], d, value, grad);
    FieldSum s{grad[0], grad[1], grad[2], -value + m[a] * KernelSoftening<K>::phi(0, h[a])};
    for (std::uint32_t k = near.begin(leaf); k < near.end(leaf); ++k) {
      const std::uint32_t entry = near.partner[k], b = entry & ~DualTreeWalk::kNewtonian;
      const TreeNode& B = tree_.nodes()[b];
      if (entry & DualTreeWalk::kNewtonian)
        add_newtonian(tree_, B.begin, B.end, xa, s);
      else
        add_softened<K>(tree_, B.begin, B.end, a, xa, h[a], s);
    }
    const std::uint32_t i = tree_.order()[a];
    acceleration[3 * i] = opt_.G * s.ax;
    acceleration[3 * i + 1] = opt_.G * s.ay;
    acceleration[3 * i + 2] = opt_.G * s.az;
    potential[i] = opt_.G * s.pot;
  }
}

template class TreeGravity<CubicSpline<3>>;
template class TreeGravity<QuinticSpline<3>>;
template class TreeGravity<WendlandC2<3>>;
template class TreeGravity<WendlandC4<3>>;
template class TreeGravity<WendlandC6<3>>;

}  // namespace sphark
