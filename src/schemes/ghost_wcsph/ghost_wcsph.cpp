#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <stdexcept>
#include <variant>

#include "sphark/kernels/kernel_list.hpp"
#include "sphark/operators/artificial_viscosity.hpp"
#include "sphark/operators/density_summation.hpp"
#include "sphark/operators/tait_eos.hpp"
#include "sphark/schemes/ghost_wcsph/ghost_wcsph.hpp"
#include "ghost_halo.hpp"

namespace sphark {

namespace {
constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();
constexpr int kMaxRetries = 4;

// Where the mirror map (seed 004, eq. 15) stops being a reflection: beyond |s| = R the reflected
// point of a circle passes its centre; a plane has no such limit.
Real mirror_limit(const Wall<2>& wall) {
  if (const auto* c = std::get_if<Cylinder<2>>(&wall)) return c->R;
  return kInfinity;
}

// Half the shortest periodic length (the minimum image needs 2 r < box length); +inf if none.
Real half_period(const PeriodicBox<2>& box) {
  Real h = kInfinity;
  for (int k = 0; k < 2; ++k)
    if (box.periodic[k]) h = std::min(h, 0.5 * (box.hi[k] - box.lo[k]));
  return h;
}
}  // namespace

template <class K>
GhostWcsph<K>::GhostWcsph(std::size_t particles, GhostWcsphParams params, Wall<2> wall, PeriodicBox<2> box)
    : p_(params), n_(particles), layout_(particles), box_(box), wall_(wall), mirror_limit_(mirror_limit(wall)),
      search_(box) {
  if (particles == 0) throw std::invalid_argument("GhostWcsph: no particles");
  if (!(p_.mass > 0) || !(p_.rho0 > 0) || !(p_.sound_speed > 0) || !(p_.eta > 0))
    throw std::invalid_argument("GhostWcsph: mass, rho0, sound_speed and eta must be positive");
  layout_.add(Field::Position, 2).add(Field::Velocity, 2);
  // At most one ghost per particle: every buffer sized for 2n once, so rhs() never grows them.
  const std::size_t cap = 2 * n_;
  ghosts_.reserve(n_);
  xall_.assign(2 * cap, 0);
  vall_.assign(2 * cap, 0);
  mass_.assign(cap, p_.mass);
  rho_.assign(cap, p_.rho0);
  h_.assign(cap, p_.eta * std::sqrt(p_.mass / p_.rho0));  // eq. (5) at rho0: the first guess
  omega_.assign(cap, 1);
  pressure_.assign(cap, 0);
  q_.assign(cap, 0);
  x_prepared_.assign(2 * n_, 0);
  ghost_h_.assign(n_, 0);
  width_ = 1.25 * K::support * h_[0];
}

template <class K>
GhostWcsph<K>::~GhostWcsph() = default;

template <class K>
Real GhostWcsph<K>::min_ghost_h() const {
  Real m = kInfinity;
  for (std::size_t g = 0; g < ghosts_.size(); ++g) m = std::min(m, ghost_h_[g]);
  return m;
}

// seed 004 eq. (1) with h = eta (m/rho)^(1/D) (seed 000 eq. (5)), over real + ghost particles.
// The list radius follows the real particles' h only: a ghost's own h is the accumulation
// diagnostic, and a ghost isolated inside the obstacle has no finite root (its h stays at the
// list limit, which only matters for the accumulation event's minimum, not at all).
template <class K>
int GhostWcsph<K>::solve_densities(std::size_t total) {
  Real h_guess = 0;
  for (std::size_t i = 0; i < n_; ++i) h_guess = std::max(h_guess, h_[i]);
  const Real r_cap = 0.999 * half_period(box_);  // the minimum image needs 2 r < box length
  Real r_build = std::min(1.1 * K::support * h_guess, r_cap);
  for (int attempt = 0; attempt < kMaxRetries; ++attempt) {
    search_.build(xall_.data(), total, r_build);
    const DensitySolveStats st = solve_density<2, K>(search_, xall_.data(), mass_.data(), total, p_.eta, p_.h_tol,
                                                     r_build / K::support, h_.data(), rho_.data(), omega_.data(), n_,
                                                     h_given_ ? n_ : 0);
    if (st.not_converged > 0) {
      error_ = "h-rho solve did not converge for " + std::to_string(st.not_converged) + " particle(s)";
      return 1;
    }
    if (st.outside_list == 0) {
      h_given_ = false;
      return 0;
    }
    if (r_build >= r_cap) {
      error_ = "support radius 2h exceeds half the box (h = " + std::to_string(st.h_max) + ")";
      return 1;
    }
    r_build = std::min(1.1 * K::support * st.h_max, r_cap);
  }
  error_ = "h-rho solve: neighbour radius did not settle";
  return 1;
}

// The state is finite (the stepper's guard checks it before every call).
template <class K>
int GhostWcsph<K>::prepare(const Real* y) {
  if (halo_) return distributed_prepare(y, true);  // collective (ghost_wcsph_distributed.cpp)
  {
    const Real* x = y + layout_.offset(Field::Position);
    const Real* v = y + layout_.offset(Field::Velocity);
    for (int attempt = 0; attempt < kMaxRetries; ++attempt) {
      ghosts_.clear();
      // seed 004 §2: ghosts of every particle within the layer, at Psi0(s) (mirror, eq. 15) or
      // Psi(s) (eq. 21); particles beyond Psi's range get none (OnInvalid::Skip).
      // The mirror map is defined for |s| <= R only: beyond, the reflected point passes the centre.
      const Real width = p_.map == GhostMap::Mirror ? std::min(width_, mirror_limit_) : width_;
      const GhostOptions opt{width, p_.map, p_.velocity, OnInvalid::Skip};
      ghosts_.append(wall_, x, v, n_, opt, &box_);
      const std::size_t g = ghosts_.size(), total = n_ + g;
      std::copy(x, x + 2 * n_, xall_.begin());
      std::copy(v, v + 2 * n_, vall_.begin());
      std::copy(ghosts_.positions(), ghosts_.positions() + 2 * g, xall_.begin() + 2 * n_);
      std::copy(ghosts_.velocities(), ghosts_.velocities() + 2 * g, vall_.begin() + 2 * n_);
      for (std::size_t k = 0; k < g; ++k) h_[n_ + k] = h_[ghosts_.sources()[k]];  // first guess
      if (int bad = solve_densities(total)) return bad;
      const Real h_max = *std::max_element(h_.begin(), h_.begin() + n_);
      const bool covered = K::support * h_max <= width_ || width < width_;
      width_ = 1.15 * K::support * h_max;  // ghost layer as thick as the largest real support
      if (!covered) continue;
      // A ghost's own support radius (eq. 1 at its position) is kept for the accumulation event;
      // the ghost then carries the fields of its inner particle (seed 004 §1-2: "the density,
      // temperature and pressure fields of the ghost particle are set equal to their inner counterpart").
      std::copy(h_.begin() + n_, h_.begin() + n_ + g, ghost_h_.begin());
      ghosts_.gather_scalar(rho_.data(), rho_.data() + n_);  // sources are real particles (< n_)
      ghosts_.gather_scalar(h_.data(), h_.data() + n_);
      ghosts_.gather_scalar(omega_.data(), omega_.data() + n_);
      h_min_ = *std::min_element(h_.begin(), h_.begin() + n_);
      pressures(total);
      std::copy(x, x + 2 * n_, x_prepared_.begin());
      prepared_ = true;
      return 0;
    }
    error_ = "ghost layer width did not settle";
    return 1;
  }
}

// P (seed 000, eq. (26): Tait plus the background) and P / (Omega rho^2) of slots 0 .. total - 1.
template <class K>
void GhostWcsph<K>::pressures(std::size_t total) {
  const Real p_b = background_pressure(p_);
  for (std::size_t i = 0; i < total; ++i) {
    pressure_[i] = tait_pressure(rho_[i], p_.rho0, p_.sound_speed) + p_b;
    q_[i] = pressure_[i] / (omega_[i] * rho_[i] * rho_[i]);
  }
}

template <class K>
void GhostWcsph<K>::resume(std::span<const Real> h) {
  if (h.empty()) return;
  check_resumed_smoothing_lengths(h, n_, "GhostWcsph::resume");
  std::copy(h.begin(), h.end(), h_.begin());
  h_given_ = true;  // the next solve takes them as the roots (solve_density's n_given)
  prepared_ = false;
}

template <class K>
int GhostWcsph<K>::prepare_if_moved(const Real* y) {
  if (halo_) return prepare_if_moved_distributed(y);  // collective
  const Real* x = y + layout_.offset(Field::Position);
  if (prepared_ && std::memcmp(x, x_prepared_.data(), 2 * n_ * sizeof(Real)) == 0) return 0;
  return prepare(y);
}

template <class K>
int GhostWcsph<K>::rhs(Real /*t*/, const Real* y, Real* ydot) {
  ++rhs_calls_;
  evaluated_y_.clear();
  if (int bad = prepare(y)) return bad;
  pair_forces(ydot);
  evaluated_y_.assign(y, y + layout_.size());
  return 0;
}

// rhs() after prepare(): the pair sums of every real particle at the prepared state, into ydot.
template <class K>
void GhostWcsph<K>::pair_forces(Real* ydot) {
  const NeighbourList& nl = search_.list();
  const Real m = p_.mass;
  Real* dx = ydot + layout_.offset(Field::Position);
  Real* dv = ydot + layout_.offset(Field::Velocity);
  Real fx = 0, fy = 0, max_acc2 = 0;
#pragma omp parallel for schedule(static) reduction(+ : fx, fy) reduction(max : max_acc2)
  for (std::size_t a = 0; a < n_; ++a) {
    const Vec<2> va(vall_[2 * a], vall_[2 * a + 1]);
    const Real ha = h_[a];
    Vec<2> acc = Vec<2>::Zero(), wall = Vec<2>::Zero();
    for (std::size_t k = nl.begin(a); k < nl.end(a); ++k) {
      const std::size_t b = nl.indices[k];
      const Real hb = h_[b];
      const Vec<2> x_ab = search_.separation(xall_.data(), a, b);
      const Real r = x_ab.norm();
      if (r >= K::support * std::max(ha, hb)) continue;
      const Vec<2> ga = K::f_over_r(r, ha) * x_ab, gb = K::f_over_r(r, hb) * x_ab;
      // grad-h form of seed 000 eq. (27) (Price 2012, eq. 35): symmetric in (a, b)
      Vec<2> term = -m * (q_[a] * ga + q_[b] * gb);
      if (p_.alpha > 0) {
        const Vec<2> v_ab = va - Vec<2>(vall_[2 * b], vall_[2 * b + 1]);
        const Real c_ab = 0.5 * (tait_sound_speed(rho_[a], p_.rho0, p_.sound_speed) +
                                 tait_sound_speed(rho_[b], p_.rho0, p_.sound_speed));
        term += monaghan_viscosity_term<2>(m, p_.alpha, c_ab, 0.5 * (rho_[a] + rho_[b]), 0.5 * (ha + hb), x_ab, v_ab,
                                           Vec<2>(0.5 * (ga + gb)));
      }
      acc += term;
      if (is_ghost(b)) wall += term;
    }
    if (p_.tau > 0) acc[0] += (p_.v0 - va[0]) / p_.tau;  // seed 004, eq. (36)
    dx[2 * a] = va[0];
    dx[2 * a + 1] = va[1];
    dv[2 * a] = acc[0];
    dv[2 * a + 1] = acc[1];
    fx += m * wall[0];
    fy += m * wall[1];
    max_acc2 = std::max(max_acc2, acc.squaredNorm());
  }
  wall_force_ = Vec<2>(fx, fy);
  max_accel_ = std::sqrt(max_acc2);
}

// max_a |dv_a/dt| of ydot, or of f(t, y) (evaluated unless y is the last state evaluated).
template <class K>
Real GhostWcsph<K>::max_acceleration(Real t, const Real* y, const Real* ydot) {
  if (!ydot) {
    bool same = evaluated_y_.size() == layout_.size() && std::equal(y, y + layout_.size(), evaluated_y_.begin());
    if (halo_) same = communicator().allreduce(std::int64_t(same ? 1 : 0), ReduceOp::Min) == 1;  // every rank evaluates
    if (!same) {
      scratch_.resize(layout_.size());
      if (rhs(t, y, scratch_.data()) != 0) return kNaN;
    }
    return max_accel_;
  }
  const Real* dv = ydot + layout_.offset(Field::Velocity);
  Real max_acc2 = 0;
  for (std::size_t a = 0; a < n_; ++a) max_acc2 = std::max(max_acc2, Vec<2>(dv[2 * a], dv[2 * a + 1]).squaredNorm());
  return std::sqrt(max_acc2);
}

template <class K>
Real GhostWcsph<K>::max_stable_dt(Real t, const Real* y, const Real* ydot) {
  const Real accel = max_acceleration(t, y, ydot);  // (before the prepare of y: rhs() prepares too)
  if (!halo_ && std::isnan(accel)) return kNaN;
  if (prepare_if_moved(y) != 0) return kNaN;  // (distributed: collective, every rank the same code)
  const Real* v = y + layout_.offset(Field::Velocity);
  Real vmax2 = 0, rho_max = 0;
  for (std::size_t a = 0; a < n_; ++a) vmax2 = std::max(vmax2, v[2 * a] * v[2 * a] + v[2 * a + 1] * v[2 * a + 1]);
  for (std::size_t i = 0; i < n_ + ghosts_.size(); ++i) rho_max = std::max(rho_max, rho_[i]);
  Real accel_max = accel;
  if (halo_) {  // the serial step from every rank's maxima (h_min_ is every rank's already)
    Real maxima[4] = {vmax2, rho_max, std::isnan(accel) ? 0 : accel, std::isnan(accel) ? Real(1) : Real(0)};
    communicator().allreduce(maxima, 4, ReduceOp::Max);
    if (maxima[3] > 0) return kNaN;
    vmax2 = maxima[0], rho_max = maxima[1], accel_max = maxima[2];
  }
  const Real c = tait_sound_speed(rho_max, p_.rho0, p_.sound_speed);
  return stable_step(h_min_, c, std::sqrt(vmax2), accel_max);
}

// Courant condition with the viscous signal speed (Monaghan 1992) and the force condition.
template <class K>
Real GhostWcsph<K>::stable_step(Real h, Real c, Real speed, Real accel) const {
  Real dt = p_.cfl * h / (c + speed + 1.2 * p_.alpha * c);
  if (accel > 0) dt = std::min(dt, p_.cfl * std::sqrt(h / accel));
  return dt;
}

template <class K>
int GhostWcsph<K>::particle_stable_dt(Real /*t*/, const Real* y, const Real* ydot, Real* dt) {
  if (halo_) throw std::logic_error("GhostWcsph::particle_stable_dt: not for a distributed scheme");
  // Without ydot the forces at y, from the densities already solved there if they were: a run's
  // diagnostics ask here after prepare(y), and a second solve would move h at round-off and with
  // it the rest of the run (it starts each solve from the last h). The ghosts' velocities follow
  // the particles' (mirrored), so new velocities at the same positions need a prepare(y) too.
  const Real* v = y + layout_.offset(Field::Velocity);
  const bool same_velocities = prepared_ && std::equal(v, v + 2 * n_, vall_.begin());
  if ((same_velocities ? prepare_if_moved(y) : prepare(y)) != 0) return 1;
  if (!ydot) {
    scratch_.resize(layout_.size());
    pair_forces(scratch_.data());
    ydot = scratch_.data();
  }
  const Real* dv = ydot + layout_.offset(Field::Velocity);
  for (std::size_t a = 0; a < n_; ++a) {
    const Real c = tait_sound_speed(rho_[a], p_.rho0, p_.sound_speed), accel = std::hypot(dv[2 * a], dv[2 * a + 1]);
    dt[a] = stable_step(h_[a], c, std::hypot(v[2 * a], v[2 * a + 1]), accel);
  }
  return 0;
}

template <class K>
int GhostWcsph<K>::roots(Real /*t*/, const Real* y, Real* g) {
  const Real* x = y + layout_.offset(Field::Position);
  Real gap = kInfinity;  // penetration: min_a -s_a, s the signed distance to the wall (< 0 in the fluid)
  std::visit(
      [&](const auto& w) {
        for (std::size_t a = 0; a < n_; ++a) gap = std::min(gap, -w.locate(box_.minimum_image(Vec<2>(x[2 * a], x[2 * a + 1]))).s);
      },
      wall_);
  g[0] = gap;
  g[1] = 1;
  if (!(p_.h_ref > 0)) return 0;
  if (int bad = prepare_if_moved(y)) return bad < 0 ? bad : -1;
  const Real hg = ghosts_.size() > 0 ? min_ghost_h() : p_.h_ref;
  g[1] = hg / p_.h_ref - p_.accumulation;
  return 0;
}

#define SPHARK_GHOST_WCSPH(K) template class GhostWcsph<K<2>>;
SPHARK_KERNELS(SPHARK_GHOST_WCSPH)
#undef SPHARK_GHOST_WCSPH

}  // namespace sphark
