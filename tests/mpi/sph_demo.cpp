#include "sph_demo.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sphark/integrate/callback_errors.hpp"
#include "sphark/kernels/kernels.hpp"
#include "sphark/operators/artificial_viscosity.hpp"
#include "sphark/operators/pressure_force.hpp"
#include "sphark/operators/tait_eos.hpp"

namespace sphark::testing {
namespace {

using Kernel = WendlandC2<2>;

Vec<2> at(const std::vector<Real>& a, std::size_t i) { return Vec<2>(a[2 * i], a[2 * i + 1]); }

}  // namespace

SphDemo::SphDemo(Communicator comm, PeriodicBox<2> box, SphDemoParams p)
    : comm_(comm), box_(box), p_(p), plan_(comm, box), search_(box) {}

void SphDemo::set_particles(std::vector<std::int64_t> ids, std::vector<Real> mass, std::vector<Real> h) {
  ids_ = std::move(ids);
  m_ = std::move(mass);
  h_ = std::move(h);
  plan_built_ = false;  // other particles: a new plan at the next rhs()
}

// Steps 1-2: the plan (kept while valid: one collective check), then x and v of the halo.
void SphDemo::gather_halo(const Real* y) {
  const std::size_t n = count();
  const Real* x = y;
  std::vector<Real>& r = r_all_;
  r.resize(n);
  for (std::size_t a = 0; a < n; ++a) r[a] = Kernel::support * h_[a];
  if (!plan_built_ || !plan_.still_valid(x, r.data())) {
    const Real h_min = comm_.allreduce(n ? *std::min_element(h_.begin(), h_.end()) : 1e300, ReduceOp::Min);
    plan_.build(x, r.data(), ids_.data(), n, p_.skin_h * h_min);
    plan_built_ = true;
    const std::size_t all = n + plan_.halo();
    m_all_.assign(m_.begin(), m_.end());
    h_all_.assign(h_.begin(), h_.end());
    m_all_.resize(all);
    h_all_.resize(all);
    plan_.exchange({{m_all_.data(), 1}, {h_all_.data(), 1}});
    keys_.resize(all);
    for (std::size_t a = 0; a < n; ++a) keys_[a] = static_cast<std::uint32_t>(ids_[a]);
    for (std::size_t k = 0; k < plan_.halo(); ++k) keys_[n + k] = static_cast<std::uint32_t>(plan_.halo_ids()[k]);
  }
  const std::size_t all = n + plan_.halo();
  x_.assign(y, y + 2 * n);
  v_.assign(y + 2 * n, y + 4 * n);
  x_.resize(2 * all);
  v_.resize(2 * all);
  plan_.exchange({{x_.data(), 2}, {v_.data(), 2}});
  r.resize(all);
  for (std::size_t b = 0; b < all; ++b) r[b] = Kernel::support * h_all_[b];
}

// Step 4 for the local particles; 1 (recoverable) for a non-finite or non-positive density.
int SphDemo::density_and_pressure() {
  const std::size_t n = count(), all = n + plan_.halo();
  rho_.assign(all, 0.0);
  p_all_.assign(all, 0.0);
  const NeighbourList& L = search_.list();
  int code = 0;
  for (std::size_t a = 0; a < n; ++a) {
    Real rho = m_all_[a] * Kernel::w(0, h_all_[a]);  // seed 000, eq. (4), self term
    for (std::size_t k = L.begin(a); k < L.end(a); ++k) {
      const std::size_t b = L.indices[k];
      const Real r = search_.separation(x_.data(), a, b).norm();
      rho += m_all_[b] * Kernel::w(r, 0.5 * (h_all_[a] + h_all_[b]));
    }
    rho_[a] = rho;
    p_all_[a] = tait_pressure(rho, p_.rho0, p_.sound_speed);  // seed 000, eq. (26)
    if (!(rho > 0) || !std::isfinite(rho)) code = 1, error_ = "density of particle " + std::to_string(ids_[a]);
  }
  return code;
}

// Step 7: seed 000, eq. (27) and Monaghan viscosity, each pair in the row's (global id) order.
void SphDemo::forces(Real* ydot) const {
  const std::size_t n = count();
  const NeighbourList& L = search_.list();
  for (std::size_t a = 0; a < n; ++a) {
    Vec<2> acc = Vec<2>::Zero();
    const Real pa = p_all_[a] / (rho_[a] * rho_[a]);
    for (std::size_t k = L.begin(a); k < L.end(a); ++k) {
      const std::size_t b = L.indices[k];
      const Vec<2> x_ab = search_.separation(x_.data(), a, b);
      const Real h_ab = 0.5 * (h_all_[a] + h_all_[b]), r = x_ab.norm();
      if (r >= Kernel::support * h_ab || r == 0) continue;
      const Vec<2> grad = Kernel::f_over_r(r, h_ab) * x_ab;
      acc += pressure_acceleration_term<2>(m_all_[b], pa, p_all_[b] / (rho_[b] * rho_[b]), grad);
      const Real c_ab = 0.5 * (tait_sound_speed(rho_[a], p_.rho0, p_.sound_speed) +
                               tait_sound_speed(rho_[b], p_.rho0, p_.sound_speed));
      acc += monaghan_viscosity_term<2>(m_all_[b], p_.alpha, c_ab, 0.5 * (rho_[a] + rho_[b]), h_ab, x_ab,
                                        at(v_, a) - at(v_, b), grad);
    }
    ydot[2 * a] = v_[2 * a];
    ydot[2 * a + 1] = v_[2 * a + 1];
    ydot[2 * n + 2 * a] = acc[0];
    ydot[2 * n + 2 * a + 1] = acc[1];
  }
}

int SphDemo::rhs(Real, const Real* y, Real* ydot) noexcept {
  try {
    gather_halo(y);
    const std::size_t all = count() + plan_.halo();
    const Real r_max = all ? *std::max_element(r_all_.begin(), r_all_.end()) : 1.0;
    search_.build(x_.data(), all, r_max, keys_.data(), r_all_.data());
    const int local = density_and_pressure();
    std::string message = error_;
    if (const int code = comm_.agree(local, message)) {
      error_ = message;
      return code;
    }
    plan_.exchange({{rho_.data(), 1}, {p_all_.data(), 1}});
    forces(ydot);
    return 0;
  } catch (...) {  // a CollectiveError is thrown on every rank: all return here together
    error_ = current_exception_message("SphDemo::rhs");
    return -1;
  }
}

Real SphDemo::max_stable_dt(Real, const Real* y, const Real*) noexcept {
  const std::size_t n = count();
  Real v_max = 0, h_min = std::numeric_limits<Real>::infinity();
  for (std::size_t a = 0; a < n; ++a) {
    v_max = std::max(v_max, std::hypot(y[2 * n + 2 * a], y[2 * n + 2 * a + 1]));
    h_min = std::min(h_min, h_[a]);
  }
  return 0.2 * h_min / (p_.sound_speed + v_max);  // +inf on a rank without particles
}

}  // namespace sphark::testing
