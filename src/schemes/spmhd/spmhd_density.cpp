// Neighbour lists (Verlet skin) and the density / smoothing-length solve of SpmhdScheme
// (seed 000, eqs. (4)-(5); Omega as in sphark/operators/density_summation.hpp).
//
// Speed: each particle's Newton iteration needs the sums at several trial h. The candidate
// neighbours (r^2, r, m_b) are gathered ONCE per particle into a per-thread buffer, and every
// Newton step sums over that buffer (same neighbours, same order, same kernel calls as
// density_sum(): the result is bit-identical to iterating over the lists).
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sphark/core/profile.hpp"
#include "sphark/operators/density_summation.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {

template <int D, class K>
void SpmhdScheme<D, K>::build_neighbours(const Real* x, Real radius) {
  ns_.build(x, n_, radius);
  built_ = true;
  ++builds_;
  const NeighbourList& L = ns_.list();
  std::size_t longest = 0;
  for (std::size_t i = 0; i < n_; ++i) longest = std::max(longest, L.count(i));
  max_list_ = longest;
}

// Verlet lists built with radius R = support * h_est * (1 + skin). A pair closer than
// support * h now was closer than support * h + 2 * disp at the build, so the lists serve every
// h <= (R - 2 disp) / support. The density solve reports particles that need more; then rebuild.
template <int D, class K>
void SpmhdScheme<D, K>::ensure_neighbours_and_density(const Real* x) {
  if (h_[0] <= 0) {
    Vec<D> lo = Eigen::Map<const Vec<D>>(x), hi = lo;
    for (std::size_t i = 1; i < n_; ++i) {
      lo = lo.cwiseMin(Eigen::Map<const Vec<D>>(x + D * i));
      hi = hi.cwiseMax(Eigen::Map<const Vec<D>>(x + D * i));
    }
    const Real volume = (hi - lo).prod();
    std::fill(h_.begin(), h_.end(), opt_.eta * std::pow(volume / static_cast<Real>(n_), 1.0 / D));
  }
  Real h_est = *std::max_element(h_.begin(), h_.end());
  for (int attempt = 0; attempt < 8; ++attempt) {
    Real cap = 0;
    {
      ScopedPhase timer(Phase::Neighbours);
      if (built_) {
        const Real disp = opt_.evolve_particles ? ns_.max_displacement_since_build(x) : 0;
        cap = (ns_.radius() - 2 * disp) / K::support;
      }
      if (!built_ || cap < h_est) {
        build_neighbours(x, K::support * h_est * (1 + opt_.skin));
        cap = ns_.radius() / K::support;
      }
    }
    ScopedPhase timer(Phase::DensityH);
    const DensityStats st = solve_density(x, cap);
    if (st.outside_list == 0) {
      if (st.not_converged > 0) throw std::runtime_error("density: h iteration did not converge");
      return;
    }
    h_est = std::max(st.h_max, cap) * 1.5;
  }
  throw std::runtime_error("density: smoothing lengths keep growing beyond the neighbour lists");
}

// Solves (4)-(5) for every particle (Newton-Raphson with a bisection fallback, as
// sphark::solve_density); h_ holds the initial guess (the previous h). h_list: the largest h
// the lists can serve.
template <int D, class K>
typename SpmhdScheme<D, K>::DensityStats SpmhdScheme<D, K>::solve_density(const Real* x, Real h_list) {
  const int threads = omp_get_max_threads();
  const std::size_t stride = 3 * max_list_;
  if (cand_.size() < stride * static_cast<std::size_t>(threads)) cand_.resize(stride * threads);
  const NeighbourList& L = ns_.list();
  const Real* m = m_.data();
  const Real r_list2 = (K::support * h_list) * (K::support * h_list);
  const Real eta_d = std::pow(opt_.eta, D), tol = opt_.h_tolerance;
  std::size_t not_converged = 0, outside = 0;
  Real h_max = 0;
#pragma omp parallel reduction(+ : not_converged, outside) reduction(max : h_max)
  {
    Real* r2c = cand_.data() + stride * static_cast<std::size_t>(omp_get_thread_num());
    Real* rc = r2c + max_list_;
    Real* mc = rc + max_list_;
#pragma omp for schedule(dynamic, 64)
    for (std::size_t i = 0; i < n_; ++i) {
      // Candidates: every listed neighbour that any trial h <= h_list can reach, in list order.
      std::size_t nc = 0;
      for (std::size_t k = L.begin(i); k < L.end(i); ++k) {
        const std::size_t j = L.indices[k];
        const Real r2 = ns_.separation(x, i, j).squaredNorm();
        if (r2 >= r_list2) continue;
        r2c[nc] = r2;
        rc[nc] = std::sqrt(r2);
        mc[nc] = m[j];
        ++nc;
      }
      // rho(h) and drho/dh at smoothing length hh, self term first (seed 000, eq. (4)).
      auto density_at = [&](Real hh, Real& rho, Real& drho_dh) {
        rho = m[i] * K::w(0, hh);
        drho_dh = m[i] * kernel_dw_dh<D, K>(0, hh);
        const Real r_max2 = (K::support * hh) * (K::support * hh);
        for (std::size_t c = 0; c < nc; ++c) {
          if (r2c[c] >= r_max2) continue;
          rho += mc[c] * K::w(rc[c], hh);
          drho_dh += mc[c] * kernel_dw_dh<D, K>(rc[c], hh);
        }
      };
      const Real m_eta = m[i] * eta_d;
      Real hh = std::min(h_[i], h_list);
      Real lo = 0, hi = h_list;  // bracket: f < 0 below the root, f > 0 above (f increasing)
      bool converged = false;
      Real r = 0, dr = 0;
      for (int it = 0; it < 100 && !converged; ++it) {
        density_at(hh, r, dr);
        const Real rho_h = m_eta / std::pow(hh, D);  // seed 000, eq. (5): rho(h) = m (eta / h)^D
        const Real f = r - rho_h, df = dr + D * rho_h / hh;
        if (f < 0) lo = std::max(lo, hh); else hi = std::min(hi, hh);
        Real h_new = (df > 0) ? hh - f / df : -1;
        if (!(h_new >= lo && h_new <= hi) || it > 30) h_new = 0.5 * (lo + hi);  // bisection fallback
        converged = std::abs(h_new - hh) < tol * hh;
        hh = h_new;
      }
      if (!converged) ++not_converged;
      if (hh >= h_list * (1 - 1e-12)) ++outside;
      density_at(hh, r, dr);
      h_[i] = hh;
      rho_[i] = r;
      omega_[i] = 1 + hh / (D * r) * dr;  // dh/drho = -h / (D rho)
      h_max = std::max(h_max, hh);
    }
  }
  return {not_converged, outside, h_max};
}

#define SPHARK_SPMHD_DENSITY(D, K)                                                              \
  template void SpmhdScheme<D, K>::build_neighbours(const Real*, Real);                         \
  template void SpmhdScheme<D, K>::ensure_neighbours_and_density(const Real*);                  \
  template SpmhdScheme<D, K>::DensityStats SpmhdScheme<D, K>::solve_density(const Real*, Real);
SPHARK_SPMHD_DENSITY(2, CubicSpline<2>)
SPHARK_SPMHD_DENSITY(3, CubicSpline<3>)
#undef SPHARK_SPMHD_DENSITY

}  // namespace sphark
