// The cylinder lattice at low resolution (seed 004, §8.2) as a stepper-study scene: 100
// particles around the obstacle with density-preserving ghosts regenerated in every RHS, driven
// at v0 = 0.5 from rest for one time unit. The RHS has a ghost set that changes with the
// positions (a discontinuous right-hand side), which is what this scene adds to the study.
#include <cmath>
#include <limits>

#include "sphark/operators/tait_eos.hpp"
#include "sphark/scenes/cylinder_lattice/lattice_run.hpp"
#include "sphark/study/study_scene.hpp"

namespace sphark {
namespace {

class LatticeProblem final : public StudyProblem {
 public:
  LatticeProblem(const LatticeRunConfig& cfg, const std::vector<Real>& x0)
      : sys_(cfg.particles, lattice_params(cfg.params, cfg.particles)), y0_(sys_.size(), 0.0) {
    std::copy(x0.begin(), x0.end(), y0_.begin() + static_cast<std::ptrdiff_t>(sys_.position_offset()));
  }
  OdeSystem& system() override { return sys_; }
  const std::vector<Real>& y0() const override { return y0_; }
  std::vector<Real> absolute_tolerance(Real rtol) const override {
    std::vector<Real> atol(sys_.size());
    const LatticeParams& p = sys_.params();
    const Real x_scale = p.radius, v_scale = std::max(p.v0, Real(1e-3));
    for (std::size_t k = 0; k < atol.size(); ++k) atol[k] = rtol * (k < sys_.velocity_offset() ? x_scale : v_scale);
    return atol;
  }
  // Blow-up measure of the stability bisection (StudyProblem::energy). The flow is driven from
  // rest, so its energy rises legitimately (by 15 % within t = 0.05); the value returned stays at
  // E_cap = M (2 v0)^2 / 2 (every particle at twice the driving speed) while the physical energy
  // is below it and follows it above, so a trial is unstable only when the physical energy
  // exceeds 1.01 E_cap (or turns non-finite) — a blow-up, not the driving.
  Real energy(Real, const Real* y) override {
    const Real e = physical_energy(y);
    if (!std::isfinite(e)) return std::numeric_limits<Real>::infinity();
    const LatticeParams& p = sys_.params();
    const Real e_cap = 0.5 * p.mass * static_cast<Real>(sys_.particles()) * 4 * p.v0 * p.v0;
    return e_cap + std::max(Real(0), e - e_cap);
  }

 private:
  // Kinetic + internal energy (integral of P/rho^2, Tait + background pressure) of the real particles.
  Real physical_energy(const Real* y) {
    if (sys_.prepare(y) != 0) return std::numeric_limits<Real>::infinity();
    const LatticeParams& p = sys_.params();
    Real e = 0;
    for (std::size_t a = 0; a < sys_.particles(); ++a) {
      const Real* v = y + sys_.velocity_offset() + 2 * a;
      const Real r = sys_.density()[a];
      e += 0.5 * p.mass * (v[0] * v[0] + v[1] * v[1]);
      e += p.mass * tait_specific_energy(r, p.rho0, p.sound_speed, background_pressure(p));
    }
    return e;
  }

 private:
  LatticeSystem sys_;
  std::vector<Real> y0_;
};

class LatticeStudyScene final : public StudyScene {
 public:
  explicit LatticeStudyScene(const StudySceneOptions& o) {
    cfg_.params.map = GhostMap::DensityPreserving;
    cfg_.params.v0 = 0.5;
    cfg_.params.cfl = 1.0;  // max_stable_dt is then the CFL unit
    if (o.spacing > 0) {
      const Real L = 2 * cfg_.params.half_box, area = L * L - kPi * cfg_.params.radius * cfg_.params.radius;
      cfg_.particles = static_cast<std::size_t>(std::lround(area / (o.spacing * o.spacing)));
    }
    t_end_ = o.t_end > 0 ? o.t_end : 1.0;
    const int outputs = o.outputs > 0 ? o.outputs : 10;
    for (int k = 1; k <= outputs; ++k) times_.push_back(t_end_ * k / outputs);
    x0_ = initial_positions(cfg_);
    LatticeProblem probe(cfg_, x0_);
    cfl_unit_ = probe.system().max_stable_dt(0, probe.y0().data(), nullptr);
  }
  std::string name() const override { return "lattice"; }
  std::string description() const override {
    return "cylinder lattice, " + std::to_string(cfg_.particles) + " particles, nonlinear ghosts, v0 0.5, t_end " +
           std::to_string(t_end_);
  }
  std::unique_ptr<StudyProblem> build() const override { return std::make_unique<LatticeProblem>(cfg_, x0_); }
  Real t_end() const override { return t_end_; }
  std::vector<Real> output_times() const override { return times_; }
  Real cfl_unit() const override { return cfl_unit_; }
  Real exact_error(Real, const Real*) const override { return std::numeric_limits<Real>::quiet_NaN(); }
  // RMS velocity difference against the reference run, relative to v0.
  Real time_error(const Real* y, const Real* y_ref) const override {
    const std::size_t n = cfg_.particles, o = 2 * n;  // layout: x (2n) then v (2n)
    Real sum = 0;
    for (std::size_t k = o; k < o + 2 * n; ++k) sum += (y[k] - y_ref[k]) * (y[k] - y_ref[k]);
    return std::sqrt(sum / static_cast<Real>(n)) / cfg_.params.v0;
  }
  // RMS minimum-image position difference, in units of the obstacle radius.
  Real position_error(const Real* y, const Real* y_ref) const override {
    const Real L = 2 * cfg_.params.half_box;
    Real sum = 0;
    for (std::size_t k = 0; k < 2 * cfg_.particles; ++k) {
      Real d = y[k] - y_ref[k];
      d -= L * std::nearbyint(d / L);
      sum += d * d;
    }
    return std::sqrt(sum / static_cast<Real>(cfg_.particles)) / cfg_.params.radius;
  }
  std::string error_description() const override {
    return "RMS velocity difference against the reference run, relative to v0 (no exact solution)";
  }

 private:
  LatticeRunConfig cfg_;
  std::vector<Real> x0_;
  Real t_end_ = 1;
  std::vector<Real> times_;
  Real cfl_unit_ = 0;
};

}  // namespace

void register_cylinder_lattice_study_scenes(StudySceneRegistry& r) {
  r.push_back({"lattice", [](const StudySceneOptions& o) -> std::unique_ptr<StudyScene> {
                 return std::make_unique<LatticeStudyScene>(o);
               }});
}

}  // namespace sphark
