// Orszag-Tang (seed 000, §IV-B) as a stepper-study scene: the "cleaning" variant of
// examples/orszag_tang (constrained cleaning, sigma = 0.3, artificial viscosity and
// conductivity on, no resistivity) on a small hexagonal lattice (default 16 x 18 = 288
// particles, t_end = 0.5: the shocks have formed). No exact solution: the error is the L1
// density difference against a tight-tolerance reference run of the same particles, particle by
// particle (Lagrangian): (1/N) sum_a |rho_a - rho_ref,a| / rho0, with rho by summation (eq. (4)).
#include <cmath>
#include <limits>
#include <algorithm>
#include <map>
#include <stdexcept>

#include "sphark/diagnostics/spmhd_diagnostics.hpp"
#include "sphark/scenes/orszag_tang/orszag_tang.hpp"
#include "sphark/study/study_scene.hpp"

namespace sphark {
namespace {

const Real kB0 = 1 / std::sqrt(4 * kPi);

class OrszagTangProblem final : public StudyProblem {
 public:
  OrszagTangProblem(const OrszagTangParams& params, Real ch0) : ot_("cleaning", params), ch0_(ch0) {}
  OdeSystem& system() override { return ot_.scheme; }
  const std::vector<Real>& y0() const override { return ot_.y0; }
  // rtol times each field's scale: box 1, |v| 1, u0, B0, c_h(0) B0 for psi.
  std::vector<Real> absolute_tolerance(Real rtol) const override {
    const StateLayout& L = ot_.scheme.layout();
    std::vector<Real> a(ot_.scheme.size(), rtol);
    const auto set = [&](Field f, Real scale) {
      if (L.has(f)) std::fill(a.begin() + L.offset(f), a.begin() + L.offset(f) + L.field_size(f), rtol * scale);
    };
    set(Field::InternalEnergy, kOrszagTangPressure / ((ot_.scheme.options().gamma - 1) * kOrszagTangRho));
    set(Field::MagneticField, kB0);
    set(Field::Psi, kB0 * ch0_);
    return a;
  }
  Real energy(Real t, const Real* y) override { return spmhd_diagnostics(ot_.scheme, t, y).total_energy; }

 private:
  OrszagTang ot_;
  Real ch0_;
};

class OrszagTangStudyScene final : public StudyScene {
 public:
  explicit OrszagTangStudyScene(const StudySceneOptions& so) {
    nx_ = so.spacing > 0 ? static_cast<int>(std::lround(1 / so.spacing)) : 16;
    if (nx_ < 8) throw std::invalid_argument("spacing=" + std::to_string(so.spacing) + ": orszag_tang needs 1/spacing >= 8");
    t_end_ = so.t_end > 0 ? so.t_end : 0.5;
    const int outputs = so.outputs > 0 ? so.outputs : 10;
    for (int k = 1; k <= outputs; ++k) times_.push_back(t_end_ * k / outputs);
    params_.nx = nx_;
    params_.sigma = 0.3;
    params_.overclean = 1;  // c_h = the fastest wave speed
    params_.courant = 1.0;  // max_stable_dt = h / v_sig: the CFL unit
    params_.cleaning_courant = 0;  // the same C for the cleaning wave: h / max(v_sig, c_h)
    probe_ = std::make_unique<OrszagTang>("cleaning", params_);
    ny_ = probe_->ny;
    cfl_unit_ = probe_->scheme.max_stable_dt(0, probe_->y0.data(), nullptr);
    ch0_ = probe_->scheme.cleaning_speed();
    pos_offset_ = probe_->scheme.layout().offset(Field::Position);
  }
  std::string name() const override { return "orszag_tang"; }
  std::string description() const override {
    return "Orszag-Tang (cleaning sigma 0.3), " + std::to_string(nx_) + " x " + std::to_string(ny_) + " = " +
           std::to_string(probe_->particles.size()) + " particles, t_end " + std::to_string(t_end_);
  }
  std::unique_ptr<StudyProblem> build() const override { return std::make_unique<OrszagTangProblem>(params_, ch0_); }
  Real t_end() const override { return t_end_; }
  std::vector<Real> output_times() const override { return times_; }
  Real cfl_unit() const override { return cfl_unit_; }
  Real exact_error(Real, const Real*) const override { return std::numeric_limits<Real>::quiet_NaN(); }
  Real time_error(const Real* y, const Real* y_ref) const override {
    const std::vector<Real> rho = density(y), rho_ref = density(y_ref);
    Real sum = 0;
    for (std::size_t a = 0; a < rho.size(); ++a) sum += std::abs(rho[a] - rho_ref[a]);
    return sum / (static_cast<Real>(rho.size()) * kOrszagTangRho);
  }
  // RMS position difference (minimum image in the unit box), in units of the box.
  Real position_error(const Real* y, const Real* y_ref) const override {
    Real sum = 0;
    for (std::size_t k = pos_offset_; k < pos_offset_ + 2 * probe_->particles.size(); ++k) {
      const Real d = y[k] - y_ref[k];
      sum += (d - std::round(d)) * (d - std::round(d));
    }
    return std::sqrt(sum / static_cast<Real>(probe_->particles.size()));
  }
  std::string error_description() const override {
    return "L1 density difference per particle / rho0 vs the reference run (no exact solution)";
  }

 private:
  // rho by summation at state y; the reference run's densities are cached (compared with
  // every run of the matrix), keyed by address and checked against a copy of the state.
  std::vector<Real> density(const Real* y) const {
    const std::size_t n = probe_->scheme.size();
    auto it = cache_.find(y);
    if (it != cache_.end() && std::equal(y, y + n, it->second.first.begin())) return it->second.second;
    probe_->scheme.evaluate(0, y);
    std::vector<Real> rho = probe_->scheme.rho();
    if (cache_.size() > 256) cache_.clear();
    cache_[y] = {std::vector<Real>(y, y + n), rho};
    return rho;
  }

  int nx_ = 0, ny_ = 0;
  Real t_end_ = 0, cfl_unit_ = 0, ch0_ = 0;
  std::vector<Real> times_;
  OrszagTangParams params_;
  std::unique_ptr<OrszagTang> probe_;
  std::size_t pos_offset_ = 0;
  mutable std::map<const Real*, std::pair<std::vector<Real>, std::vector<Real>>> cache_;
};

}  // namespace

void register_orszag_tang_study_scenes(StudySceneRegistry& r) {
  r.push_back({"orszag_tang", [](const StudySceneOptions& o) -> std::unique_ptr<StudyScene> {
                 return std::make_unique<OrszagTangStudyScene>(o);
               }});
}

}  // namespace sphark
