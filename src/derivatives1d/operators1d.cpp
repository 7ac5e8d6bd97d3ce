// seed 001: CSPM, BIM and ICSPM second-derivative operators as sparse matrices.
#include "sphark/derivatives1d/operators1d.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "sphark/derivatives1d/kernel1d.hpp"

namespace sphark::d1 {

using Kernel = SeedKernel1D;
using Triplets = std::vector<Eigen::Triplet<Real>>;

Neighbours1D find_neighbours(const Eigen::VectorXd& x, Real radius) {
  const Index n = x.size();
  std::vector<Index> order(n);
  std::iota(order.begin(), order.end(), Index{0});
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return x[a] < x[b]; });
  Neighbours1D nb;
  nb.offset.assign(n + 1, 0);
  std::vector<std::pair<Index, Index>> window(n);  // [lo, hi) in sorted order, per sorted slot
  Index lo = 0, hi = 0;
  for (Index s = 0; s < n; ++s) {  // sliding window over the sorted positions
    const Real xs = x[order[s]];
    while (x[order[lo]] <= xs - radius) ++lo;
    while (hi < n && x[order[hi]] < xs + radius) ++hi;
    window[s] = {lo, hi};
    nb.offset[order[s] + 1] = hi - lo;
  }
  for (Index i = 0; i < n; ++i) nb.offset[i + 1] += nb.offset[i];
  nb.index.resize(nb.offset[n]);
  for (Index s = 0; s < n; ++s) {
    Index k = nb.offset[order[s]];
    for (Index t = window[s].first; t < window[s].second; ++t) nb.index[k++] = order[t];
  }
  return nb;
}

namespace {

void check(const Particles1D& p, Real h) {
  if (p.size() < 3) throw std::invalid_argument("derivatives1d: need at least 3 particles");
  if (!(h > 0)) throw std::invalid_argument("derivatives1d: smoothing length must be > 0");
}

// Row i of the CSPM / ICSPM matrix (seed 001, eq. (5.15), (5.17)), written without building the
// intermediate first-derivative matrix: for j != i
//   L_ij = [W_ij - m1_i W'_ij / gamma~_i] |Omega_j| / (gamma*_i kappa_i),   L_ii = -sum_{j != i} L_ij,
// which is (5.15) with <f'>_i from (3.5) substituted (both sums act on f_j - f_i).
SparseMatrix cspm_like(const Particles1D& p, Real h, bool improved) {
  check(p, h);
  const Neighbours1D nb = find_neighbours(p.x, Kernel::support * h);
  Triplets t;
  t.reserve(nb.index.size());
  std::vector<Real> w, dw;
  for (Index i = 0; i < p.size(); ++i) {
    const Index k0 = nb.offset[i], k1 = nb.offset[i + 1];
    w.resize(k1 - k0);
    dw.resize(k1 - k0);
    Real gt = 0, gs = 0, m1 = 0, m2p = 0;
    for (Index k = k0; k < k1; ++k) {
      const Index j = nb.index[k];
      const Real r = p.x[j] - p.x[i], vj = p.volume[j];
      w[k - k0] = Kernel::w(r, h) * vj;
      dw[k - k0] = Kernel::dw(-r, h) * vj;  // W'_ij at x_i - x_j
      gt += r * dw[k - k0];                  // gamma~_i, (3.6)
      gs += 0.5 * r * r * w[k - k0];         // gamma*_i, (4.8)
      m1 += r * w[k - k0];
      if (improved) m2p += 0.5 * r * r * dw[k - k0];
    }
    Real scale = 1.0 / gs;
    if (improved) scale /= 1.0 - m2p * m1 / (gt * gs);  // 1 / kappa_i, (4.14) corrected
    Real diag = 0;
    for (Index k = k0; k < k1; ++k) {
      const Index j = nb.index[k];
      if (j == i) continue;
      const Real c = (w[k - k0] - m1 * dw[k - k0] / gt) * scale;
      t.emplace_back(i, j, c);
      diag -= c;
    }
    t.emplace_back(i, i, diag);
  }
  SparseMatrix L(p.size(), p.size());
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

}  // namespace

Moments1D moments(const Particles1D& p, Real h) {
  check(p, h);
  const Index n = p.size();
  const Neighbours1D nb = find_neighbours(p.x, Kernel::support * h);
  Moments1D m;
  m.gamma = m.gamma_tilde = m.gamma_star = m.m1 = m.m2_prime = Eigen::VectorXd::Zero(n);
  for (Index i = 0; i < n; ++i) {
    for (Index k = nb.offset[i]; k < nb.offset[i + 1]; ++k) {
      const Index j = nb.index[k];
      const Real r = p.x[j] - p.x[i], w = Kernel::w(r, h) * p.volume[j];
      const Real dw = Kernel::dw(-r, h) * p.volume[j];
      m.gamma[i] += w;
      m.gamma_tilde[i] += r * dw;
      m.gamma_star[i] += 0.5 * r * r * w;
      m.m1[i] += r * w;
      m.m2_prime[i] += 0.5 * r * r * dw;
    }
  }
  m.kappa = (1.0 - (m.m2_prime.array() * m.m1.array()) /
                       (m.gamma_tilde.array() * m.gamma_star.array())).matrix();
  return m;
}

SparseMatrix cspm_first_derivative(const Particles1D& p, Real h) {
  check(p, h);
  const Neighbours1D nb = find_neighbours(p.x, Kernel::support * h);
  Triplets t;
  t.reserve(nb.index.size());
  for (Index i = 0; i < p.size(); ++i) {
    Real gt = 0;
    for (Index k = nb.offset[i]; k < nb.offset[i + 1]; ++k) {
      const Index j = nb.index[k];
      const Real r = p.x[j] - p.x[i];
      gt += r * Kernel::dw(-r, h) * p.volume[j];  // gamma~_i, (3.6)
    }
    Real diag = 0;
    for (Index k = nb.offset[i]; k < nb.offset[i + 1]; ++k) {
      const Index j = nb.index[k];
      if (j == i) continue;
      const Real c = Kernel::dw(p.x[i] - p.x[j], h) * p.volume[j] / gt;  // (3.5)
      t.emplace_back(i, j, c);
      diag -= c;
    }
    t.emplace_back(i, i, diag);
  }
  SparseMatrix D(p.size(), p.size());
  D.setFromTriplets(t.begin(), t.end());
  return D;
}

SparseMatrix cspm_second_derivative(const Particles1D& p, Real h) { return cspm_like(p, h, false); }
SparseMatrix icspm_second_derivative(const Particles1D& p, Real h) { return cspm_like(p, h, true); }

SparseMatrix bim_second_derivative(const Particles1D& p, Real h) {
  check(p, h);
  const Neighbours1D nb = find_neighbours(p.x, Kernel::support * h);
  const Index l = p.left(), r = p.right();
  const Real xl = p.x[l], xr = p.x[r];
  Triplets t;
  t.reserve(nb.index.size() + 2 * p.size());
  for (Index i = 0; i < p.size(); ++i) {
    if (p.on_boundary(i)) continue;  // 0/0 in (4.9): the paper neglects these particles
    Real gamma = 0;                   // Shepard factor, (4.10)
    for (Index k = nb.offset[i]; k < nb.offset[i + 1]; ++k) {
      const Index j = nb.index[k];
      gamma += Kernel::w(p.x[j] - p.x[i], h) * p.volume[j];
    }
    const Real s = 2.0 / gamma;
    Real diag = 0;
    for (Index k = nb.offset[i]; k < nb.offset[i + 1]; ++k) {
      const Index j = nb.index[k];
      if (j == i) continue;
      const Real dx = p.x[j] - p.x[i];
      const Real c = s * Kernel::dw(-dx, h) * p.volume[j] / dx;  // 2/gamma (f_j - f_i)/(x_j - x_i) W'_ij |Omega_j|
      t.emplace_back(i, j, c);
      diag -= c;
    }
    // boundary integral terms of (4.9), inside the factor 2/gamma_i (corrected)
    const Real br = s * Kernel::w(p.x[i] - xr, h) / (p.x[i] - xr);  // + (f_i - f_r)/(x_i - x_r) W_ir
    const Real bl = s * Kernel::w(p.x[i] - xl, h) / (p.x[i] - xl);  // - (f_i - f_l)/(x_i - x_l) W_il
    if (br != 0) t.emplace_back(i, r, -br);
    if (bl != 0) t.emplace_back(i, l, bl);
    t.emplace_back(i, i, diag + br - bl);
  }
  SparseMatrix L(p.size(), p.size());
  L.setFromTriplets(t.begin(), t.end());  // duplicates (i, l) / (i, r) are summed
  return L;
}

const char* method_name(Method m) {
  switch (m) {
    case Method::Cspm: return "CSPM";
    case Method::Bim: return "BIM";
    case Method::Icspm: return "ICSPM";
  }
  return "?";
}

SparseMatrix second_derivative(Method m, const Particles1D& p, Real h) {
  switch (m) {
    case Method::Cspm: return cspm_second_derivative(p, h);
    case Method::Bim: return bim_second_derivative(p, h);
    case Method::Icspm: return icspm_second_derivative(p, h);
  }
  throw std::invalid_argument("second_derivative: unknown method");
}

bool row_defined(Method m, const Particles1D& p, Index i) {
  return m != Method::Bim || !p.on_boundary(i);
}

}  // namespace sphark::d1
