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

#include "sphark/scenes/cleaning_disc/cleaning_disc.hpp"
#include "sphark/study/study_scene.hpp"

namespace sphark {
namespace {

const Real kB0 = 1 / std::sqrt(4 * kPi);  // field scale of eq. (40)

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

// The disc of the study: constrained cleaning, Courant number 1 (max_stable_dt = h / c_h: the CFL unit).
CleaningDisc study_disc(Real sigma, Real spacing) { return CleaningDisc(Cleaning::Constrained, sigma, spacing, 1.0); }

class DiscProblem final : public StudyProblem {
 public:
  DiscProblem(Real sigma, Real spacing) : disc_(study_disc(sigma, spacing)) { e0_ = cleaning_energy(disc_.scheme, disc_.y0.data()); }
  OdeSystem& system() override { return disc_.scheme; }
  const std::vector<Real>& y0() const override { return disc_.y0; }
  std::vector<Real> absolute_tolerance(Real rtol) const override {
    const SpmhdScheme<2>& s = disc_.scheme;
    std::vector<Real> a(s.size(), rtol * kB0);
    const std::size_t op = s.layout().offset(Field::Psi);
    std::fill(a.begin() + op, a.begin() + op + s.particles(), rtol * kB0 * s.options().fixed_ch);
    return a;
  }
  // sigma = 0: E_c. sigma > 0: max(E_c, E_c(0)) -- the damped ODE never raises E_c, so only a
  // growth above the initial value counts as a blow-up in the stability bisection.
  Real energy(Real, const Real* y) override {
    const Real e = cleaning_energy(disc_.scheme, y);
    return disc_.scheme.options().sigma > 0 ? std::max(e, e0_) : e;
  }

 private:
  CleaningDisc disc_;
  Real e0_ = 0;
};

class DiscScene final : public StudyScene {
 public:
  DiscScene(const StudySceneOptions& so, Real sigma) : sigma_(sigma) {
    spacing_ = so.spacing > 0 ? so.spacing : 0.08;
    t_end_ = so.t_end > 0 ? so.t_end : 10.0;
    const int outputs = so.outputs > 0 ? so.outputs : 20;
    for (int k = 1; k <= outputs; ++k) times_.push_back(t_end_ * k / outputs);
    probe_ = std::make_unique<CleaningDisc>(study_disc(sigma, spacing_));  // c_h frozen: E_c is an invariant of sigma = 0
    SpmhdScheme<2>& s = probe_->scheme;
    cfl_unit_ = s.max_stable_dt(0, probe_->y0.data(), nullptr);
    psi_offset_ = s.layout().offset(Field::Psi);
    b_offset_ = s.layout().offset(Field::MagneticField);
    e0_ = cleaning_energy(s, probe_->y0.data());
  }
  std::string name() const override { return sigma_ > 0 ? "disc_damped" : "disc"; }
  std::string description() const override {
    return "cleaning disc (fixed particles), " + std::to_string(probe_->particles.size()) + " particles (spacing " +
           std::to_string(spacing_) + "), sigma " + std::to_string(sigma_) + ", c_h " +
           std::to_string(probe_->scheme.options().fixed_ch) + ", t_end " + std::to_string(t_end_);
  }
  std::unique_ptr<StudyProblem> build() const override { return std::make_unique<DiscProblem>(sigma_, spacing_); }
  Real t_end() const override { return t_end_; }
  std::vector<Real> output_times() const override { return times_; }
  Real cfl_unit() const override { return cfl_unit_; }
  // sigma = 0: |E_c(t) - E_c(0)| / E_c(0) (exact invariant). sigma > 0: no exact solution.
  Real exact_error(Real, const Real* y) const override {
    if (sigma_ > 0) return std::numeric_limits<Real>::quiet_NaN();
    return std::abs(cleaning_energy(probe_->scheme, y) - e0_) / e0_;
  }
  // Relative cleaning-energy difference against the reference run, |E_c - E_c,ref| / E_c(0).
  Real time_error(const Real* y, const Real* y_ref) const override {
    return std::abs(cleaning_energy(probe_->scheme, y) - cleaning_energy(probe_->scheme, y_ref)) / e0_;
  }
  // The field difference: max(RMS |B - B_ref| / B0, RMS |psi - psi_ref| / (c_h B0)).
  Real position_error(const Real* y, const Real* y_ref) const override {
    const std::size_t n = probe_->particles.size();
    Real sb = 0, sp = 0;
    for (std::size_t k = b_offset_; k < b_offset_ + 3 * n; ++k) sb += (y[k] - y_ref[k]) * (y[k] - y_ref[k]);
    for (std::size_t a = psi_offset_; a < psi_offset_ + n; ++a) sp += (y[a] - y_ref[a]) * (y[a] - y_ref[a]);
    const Real nn = static_cast<Real>(n);
    return std::max(std::sqrt(sb / nn) / kB0, std::sqrt(sp / nn) / (kB0 * probe_->scheme.options().fixed_ch));
  }
  std::string error_description() const override {
    return sigma_ > 0 ? "relative cleaning-energy difference vs the reference run (no exact solution)"
                      : "relative change of the cleaning energy (an exact invariant of the sigma = 0 ODE)";
  }

 private:
  Real sigma_, spacing_ = 0, t_end_ = 0, cfl_unit_ = 0, e0_ = 0;
  std::vector<Real> times_;
  std::unique_ptr<CleaningDisc> probe_;  // evaluates rho for the energies (not thread-safe)
  std::size_t psi_offset_ = 0, b_offset_ = 0;
};

}  // namespace

// "disc": sigma = 0, the conservative cleaning subsystem; "disc_damped": sigma = 0.3.
void register_cleaning_disc_study_scenes(StudySceneRegistry& r) {
  r.push_back({"disc", [](const StudySceneOptions& o) -> std::unique_ptr<StudyScene> {
                 return std::make_unique<DiscScene>(o, 0.0);
               }});
  r.push_back({"disc_damped", [](const StudySceneOptions& o) -> std::unique_ptr<StudyScene> {
                 return std::make_unique<DiscScene>(o, 0.3);
               }});
}

}  // namespace sphark
