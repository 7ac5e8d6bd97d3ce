#pragma once
// Density by summation with a self-consistent variable smoothing length, and the grad-h term.
//
//   rho_a   = sum_b m_b W_ab(h_a)                          seed 000, eq. (4)  (b includes a)
//   h_a     = eta (m_a / rho_a)^(1/D)                      seed 000, eq. (5)
//   Omega_a = 1 - (dh_a/drho_a) sum_b m_b dW_ab(h_a)/dh_a  (Price 2012, JCP 231, eq. 29)
//
// Per particle, f(h) = sum_b m_b W_ab(h) - m_a (eta/h)^D is solved by Newton-Raphson
// (f'(h) = sum_b m_b dW/dh + D m_a eta^D / h^(D+1)), with a bisection fallback when Newton leaves
// the bracket or stalls. Converged when |h_new - h| < tol * h (tol = 1e-10 by default: Newton
// converges quadratically, so the returned h satisfies (5) to round-off in practice).
// rho and Omega returned are evaluated AT the returned h, so the scheme is self-consistent.
//
// The neighbour lists must contain every pair closer than K::support * h_a; the solver reports
// (without writing a wrong answer) when the converged h needs a larger list radius.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/neighbours/neighbour_search.hpp"

namespace sphark {

struct DensitySolveStats {
  std::size_t not_converged = 0;   // particles that hit the iteration limit
  std::size_t outside_list = 0;    // particles whose h needs a larger neighbour radius
  Real h_max = 0;                  // largest h found
};

// dW/dh at fixed r:  W = sigma/h^D f(r/h)  =>  dW/dh = -(D W + r dW/dr) / h.
template <int D, class K>
inline Real kernel_dw_dh(Real r, Real h) {
  return -(D * K::w(r, h) + r * r * K::f_over_r(r, h)) / h;
}

// Sums rho(h) and drho/dh for particle i at smoothing length h (self term included).
template <int D, class K>
inline void density_sum(const NeighbourSearch<D>& ns, const Real* x, const Real* m, std::size_t i, Real h,
                        Real& rho, Real& drho_dh) {
  rho = m[i] * K::w(0, h);
  drho_dh = m[i] * kernel_dw_dh<D, K>(0, h);
  const NeighbourList& L = ns.list();
  const Real r_max2 = (K::support * h) * (K::support * h);
  for (std::size_t k = L.begin(i); k < L.end(i); ++k) {
    const std::size_t j = L.indices[k];
    const Real r2 = ns.separation(x, i, j).squaredNorm();
    if (r2 >= r_max2) continue;
    const Real r = std::sqrt(r2);
    rho += m[j] * K::w(r, h);
    drho_dh += m[j] * kernel_dw_dh<D, K>(r, h);
  }
}

// The last iterate of solve_smoothing_length: the h at which the sums were last evaluated, the
// sums there, and the h the Newton (or bisection) step from it gives.
struct SmoothingLengthIterate {
  Real h = 0, rho = 0, drho_dh = 0;
  Real h_next = 0;
  // rho at h_next to first order, rho + (h_next - h) drho/dh: within (h_next - h)^2 |rho''| / 2 of
  // the sum at h_next, below round-off once |h_next - h| < tol h with tol <= 1e-8
  Real rho_next() const { return rho + (h_next - h) * drho_dh; }
};

// seed 000, eqs. (4)-(5): the h of one particle, root of f(h) = rho(h) - m (eta/h)^D on
// (0, h_list], by Newton-Raphson from h_start with a bisection fallback when Newton leaves the
// bracket or stalls (> 30 iterations), to |h_next - h| < tol h. sums(h, rho, drho_dh) evaluates
// the density sum (4) and its h-derivative at h; m_eta = m eta^D. Counts the iterations (one sum
// each). The root is h_next of the iterate returned: Newton's error there is of second order.
template <int D, class Sums, class Count>
SmoothingLengthIterate solve_smoothing_length(Sums&& sums, Real h_start, Real h_list, Real m_eta, Real tol,
                                              bool& converged, Count& iterations) {
  SmoothingLengthIterate it;
  it.h_next = std::min(h_start, h_list);
  Real lo = 0, hi = h_list;  // bracket: f < 0 below the root, f > 0 above (f increasing)
  converged = false;
  for (int k = 0; k < 100 && !converged; ++k) {
    ++iterations;
    it.h = it.h_next;
    sums(it.h, it.rho, it.drho_dh);
    const Real rho_h = m_eta / std::pow(it.h, D);  // seed 000, eq. (5): rho(h) = m (eta / h)^D
    const Real f = it.rho - rho_h, df = it.drho_dh + D * rho_h / it.h;
    if (f < 0) lo = std::max(lo, it.h); else hi = std::min(hi, it.h);
    Real h_new = (df > 0) ? it.h - f / df : -1;
    if (!(h_new >= lo && h_new <= hi) || k > 30) h_new = 0.5 * (lo + hi);  // bisection fallback
    converged = std::abs(h_new - it.h) < tol * it.h;
    it.h_next = h_new;
  }
  return it;
}

// Is h already a root to the tolerance of solve_smoothing_length (one Newton step from it would
// move it by less than tol h)? For a restart that hands back the roots of the interrupted run.
template <int D, class Sums>
bool is_smoothing_length_root(Sums&& sums, Real h, Real m_eta, Real tol) {
  Real r = 0, dr = 0;
  sums(h, r, dr);
  const Real rho_h = m_eta / std::pow(h, D);  // seed 000, eq. (5)
  const Real f = r - rho_h, df = dr + D * rho_h / h;
  return df > 0 && std::abs(f / df) < tol * h;
}

// The smoothing lengths a restart hands back (OdeSystem::resume): one per particle, each positive
// and finite; otherwise std::invalid_argument "<who>: ..." saying which.
inline void check_resumed_smoothing_lengths(std::span<const Real> h, std::size_t particles, const std::string& who) {
  if (h.size() != particles)
    throw std::invalid_argument(who + ": " + std::to_string(h.size()) + " smoothing lengths for " +
                                std::to_string(particles) + " particles");
  for (std::size_t i = 0; i < particles; ++i)
    if (!(std::isfinite(h[i]) && h[i] > 0))
      throw std::invalid_argument(who + ": the smoothing length of particle " + std::to_string(i) +
                                  " is not positive and finite");
}

// After solve_smoothing_length returned h_found: does the root of f(h) = rho(h) - m (eta/h)^D lie
// beyond h_list (the lists must then serve a larger h)? The iteration cannot leave (0, h_list]:
// when the root lies beyond, it converges onto h_list itself (to within about tol). f increases
// with h, so the root lies beyond exactly when f(h_list) < 0; that sum is evaluated only when
// h_found is that close to h_list (within max(1e-6, 10 tol), relative). The one criterion of
// every density solve (solve_density below, the SPMHD scheme).
template <int D, class Sums>
bool root_beyond_list(Sums&& sums, Real h_found, Real h_list, Real m_eta, Real tol) {
  if (!(h_found > h_list * (1 - std::max(1e-6, 10 * tol)))) return false;
  Real rho = 0, drho_dh = 0;
  sums(h_list, rho, drho_dh);
  return rho < m_eta / std::pow(h_list, D);  // f(h_list) < 0, seed 000 eq. (5)
}

// Solves (4)-(5) for every particle. h is the initial guess on input (e.g. the previous h).
// h_list: the largest h the lists can serve (ns.radius() / K::support for fresh lists; less when
// particles moved since the build).
// Only particles i < n_checked count towards outside_list and h_max (default: all): a caller may
// solve extra particles (e.g. ghosts, whose own h is only a diagnostic) without letting a root
// beyond the lists (an isolated ghost has none: h -> infinity) force rebuilds; their h then stays
// at h_list.
// Particles i < n_given (default none) keep h[i] where it is already a root
// (is_smoothing_length_root): a restart hands back the roots of the interrupted run
// (OdeSystem::resume), and a Newton step from a root would move it by round-off.
template <int D, class K>
DensitySolveStats solve_density(const NeighbourSearch<D>& ns, const Real* x, const Real* m, std::size_t n,
                                Real eta, Real tol, Real h_list, Real* h, Real* rho, Real* omega,
                                std::size_t n_checked, std::size_t n_given = 0) {
  std::size_t not_converged = 0, outside = 0;
  Real h_max = 0;
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : not_converged, outside) reduction(max : h_max)
  for (std::size_t i = 0; i < n; ++i) {
    // The list entries' squared distances, distances and masses, gathered once per particle: the
    // Newton iterations below re-sum them at each trial h (same terms, same order as
    // density_sum(), so the result is bit-identical to walking the lists each time).
    static thread_local std::vector<Real> r2s, rs, ms;
    const NeighbourList& L = ns.list();
    r2s.clear(); rs.clear(); ms.clear();
    for (std::size_t k = L.begin(i); k < L.end(i); ++k) {
      const std::size_t j = L.indices[k];
      const Real r2 = ns.separation(x, i, j).squaredNorm();
      r2s.push_back(r2);
      rs.push_back(std::sqrt(r2));
      ms.push_back(m[j]);
    }
    const Real m_eta = m[i] * std::pow(eta, D);
    auto sums = [&](Real hh, Real& r, Real& dr) {  // density_sum() over the gathered entries
      r = m[i] * K::w(0, hh);
      dr = m[i] * kernel_dw_dh<D, K>(0, hh);
      const Real r_max2 = (K::support * hh) * (K::support * hh);
      for (std::size_t k = 0; k < r2s.size(); ++k) {
        if (r2s[k] >= r_max2) continue;
        r += ms[k] * K::w(rs[k], hh);
        dr += ms[k] * kernel_dw_dh<D, K>(rs[k], hh);
      }
    };
    long iterations = 0;
    Real hh = h[i];
    bool converged = i < n_given && hh <= h_list && is_smoothing_length_root<D>(sums, hh, m_eta, tol);
    if (!converged) hh = solve_smoothing_length<D>(sums, h[i], h_list, m_eta, tol, converged, iterations).h_next;
    Real r = 0;
    if (!converged) ++not_converged;
    if (i < n_checked && root_beyond_list<D>(sums, hh, h_list, m_eta, tol)) ++outside;
    Real dr;
    sums(hh, r, dr);
    h[i] = hh;
    rho[i] = r;
    omega[i] = 1 + hh / (D * r) * dr;  // dh/drho = -h / (D rho)
    if (i < n_checked) h_max = std::max(h_max, hh);
  }
  return {not_converged, outside, h_max};
}

template <int D, class K>
DensitySolveStats solve_density(const NeighbourSearch<D>& ns, const Real* x, const Real* m, std::size_t n,
                                Real eta, Real tol, Real h_list, Real* h, Real* rho, Real* omega) {
  return solve_density<D, K>(ns, x, m, n, eta, tol, h_list, h, rho, omega, n);
}

}  // namespace sphark
