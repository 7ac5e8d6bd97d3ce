// The static cleaning disc (seed 000, §IV-A) as a stepper-study scene: fixed particles, only the
// cleaning subsystem dB/dt = -grad psi (eq. (23)), dpsi/dt = -c_h^2 div B (eq. (20)) - psi/tau
// (eq. (19)), c_h frozen at t = 0 as in examples/cleaning_disc. With sigma = 0 ("disc") the
// cleaning energy E_c = sum m (B_x^2 + B_y^2) / (2 rho) + sum m psi^2 / (2 rho c_h^2) (seed 000,
// eq. (17); B_z is constant and left out) is conserved exactly by the semi-discrete ODE, so its
// relative change is the time-integration error against an exact invariant. With sigma > 0
// ("disc_damped") E_c decays; the stiff part -psi/tau is what ark-imex treats implicitly.
// Smaller than the reproduction by default: spacing 0.08 (484 particles), t_end = 10.
#include <algorithm>
#include <cmath>
#include <limits>

#include "sphark/schemes/spmhd/spmhd_setup.hpp"
#include "study_scene_factories.hpp"

namespace sphark {
namespace {

const Real kB0 = 1 / std::sqrt(4 * kPi);  // field scale of eq. (40)

SpmhdOptions disc_options(Real sigma) {
  SpmhdOptions o;
  o.evolve_particles = false;
  o.cleaning = Cleaning::Constrained;
  o.sigma = sigma;
  o.courant = 1.0;  // max_stable_dt = h / c_h: the CFL unit
  return o;
}

// E_c of state y (B and psi fields of the subsystem layout); refreshes rho via evaluate().
Real cleaning_energy(SpmhdScheme<2>& s, const Real* y) {
  s.evaluate(0.0, y);
  const std::size_t ob = s.layout().offset(Field::MagneticField), op = s.layout().offset(Field::Psi);
  const Real c2 = s.cleaning_speed() * s.cleaning_speed();
  Real e = 0;
  for (std::size_t a = 0; a < s.particles(); ++a) {
    const Real bx = y[ob + 3 * a], by = y[ob + 3 * a + 1], psi = y[op + a];
    e += s.masses()[a] * ((bx * bx + by * by) / 2 + psi * psi / (2 * c2)) / s.rho()[a];
  }
  return e;
}

class DiscProblem final : public StudyProblem {
 public:
  DiscProblem(const ParticleSet2D& p, const SpmhdOptions& o) : scheme_(p.m, o, std::nullopt, p.x), y0_(scheme_.size(), 0) {
    disc_initial_field(scheme_, p, y0_.data());
    e0_ = cleaning_energy(scheme_, y0_.data());
  }
  OdeSystem& system() override { return scheme_; }
  const std::vector<Real>& y0() const override { return y0_; }
  std::vector<Real> absolute_tolerance(Real rtol) const override {
    std::vector<Real> a(scheme_.size(), rtol * kB0);
    const std::size_t op = scheme_.layout().offset(Field::Psi);
    std::fill(a.begin() + op, a.begin() + op + scheme_.particles(), rtol * kB0 * scheme_.options().fixed_ch);
    return a;
  }
  // sigma = 0: E_c. sigma > 0: max(E_c, E_c(0)) -- the damped ODE never raises E_c, so only a
  // growth above the initial value counts as a blow-up in the stability bisection.
  Real energy(Real, const Real* y) override {
    const Real e = cleaning_energy(scheme_, y);
    return scheme_.options().sigma > 0 ? std::max(e, e0_) : e;
  }

 private:
  SpmhdScheme<2> scheme_;
  std::vector<Real> y0_;
  Real e0_ = 0;
};

class DiscScene final : public StudyScene {
 public:
  DiscScene(const StudySceneOptions& so, Real sigma) : sigma_(sigma) {
    spacing_ = so.spacing > 0 ? so.spacing : 0.08;
    t_end_ = so.t_end > 0 ? so.t_end : 10.0;
    const int outputs = so.outputs > 0 ? so.outputs : 20;
    for (int k = 1; k <= outputs; ++k) times_.push_back(t_end_ * k / outputs);
    particles_ = disc_square_lattice(1.0, spacing_, 1.0);
    options_ = disc_options(sigma);
    SpmhdScheme<2> probe(particles_.m, options_, std::nullopt, particles_.x);
    std::vector<Real> y0(probe.size(), 0);
    disc_initial_field(probe, particles_, y0.data());
    probe.evaluate(0, y0.data());
    options_.fixed_ch = probe.cleaning_speed();  // frozen: E_c is then an invariant of sigma = 0
    probe_ = std::make_unique<SpmhdScheme<2>>(particles_.m, options_, std::nullopt, particles_.x);
    cfl_unit_ = probe_->max_stable_dt(0, y0.data(), nullptr);
    psi_offset_ = probe_->layout().offset(Field::Psi);
    b_offset_ = probe_->layout().offset(Field::MagneticField);
    e0_ = cleaning_energy(*probe_, y0.data());
  }
  std::string name() const override { return sigma_ > 0 ? "disc_damped" : "disc"; }
  std::string description() const override {
    return "cleaning disc (fixed particles), " + std::to_string(particles_.size()) + " particles (spacing " +
           std::to_string(spacing_) + "), sigma " + std::to_string(sigma_) + ", c_h " +
           std::to_string(options_.fixed_ch) + ", t_end " + std::to_string(t_end_);
  }
  std::unique_ptr<StudyProblem> build() const override { return std::make_unique<DiscProblem>(particles_, options_); }
  Real t_end() const override { return t_end_; }
  std::vector<Real> output_times() const override { return times_; }
  Real cfl_unit() const override { return cfl_unit_; }
  // sigma = 0: |E_c(t) - E_c(0)| / E_c(0) (exact invariant). sigma > 0: no exact solution.
  Real exact_error(Real, const Real* y) const override {
    if (sigma_ > 0) return std::numeric_limits<Real>::quiet_NaN();
    return std::abs(cleaning_energy(*probe_, y) - e0_) / e0_;
  }
  // Relative cleaning-energy difference against the reference run, |E_c - E_c,ref| / E_c(0).
  Real time_error(const Real* y, const Real* y_ref) const override {
    return std::abs(cleaning_energy(*probe_, y) - cleaning_energy(*probe_, y_ref)) / e0_;
  }
  // The field difference: max(RMS |B - B_ref| / B0, RMS |psi - psi_ref| / (c_h B0)).
  Real position_error(const Real* y, const Real* y_ref) const override {
    const std::size_t n = particles_.size();
    Real sb = 0, sp = 0;
    for (std::size_t k = b_offset_; k < b_offset_ + 3 * n; ++k) sb += (y[k] - y_ref[k]) * (y[k] - y_ref[k]);
    for (std::size_t a = psi_offset_; a < psi_offset_ + n; ++a) sp += (y[a] - y_ref[a]) * (y[a] - y_ref[a]);
    const Real nn = static_cast<Real>(n);
    return std::max(std::sqrt(sb / nn) / kB0, std::sqrt(sp / nn) / (kB0 * options_.fixed_ch));
  }
  std::string error_description() const override {
    return sigma_ > 0 ? "relative cleaning-energy difference vs the reference run (no exact solution)"
                      : "relative change of the cleaning energy (an exact invariant of the sigma = 0 ODE)";
  }

 private:
  Real sigma_, spacing_ = 0, t_end_ = 0, cfl_unit_ = 0, e0_ = 0;
  std::vector<Real> times_;
  ParticleSet2D particles_;
  SpmhdOptions options_;
  std::unique_ptr<SpmhdScheme<2>> probe_;  // evaluates rho for the energies (not thread-safe)
  std::size_t psi_offset_ = 0, b_offset_ = 0;
};

}  // namespace

namespace detail {
std::unique_ptr<StudyScene> make_disc_study_scene(const StudySceneOptions& options, Real sigma) {
  return std::make_unique<DiscScene>(options, sigma);
}
}  // namespace detail

}  // namespace sphark
