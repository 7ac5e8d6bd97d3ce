// The water drop (seed 000, §IV-D) as a stepper-study scene: a smaller, shorter drop than the
// reproduction (spacing 0.08 -> 484 particles, t_end = 0.025: about one squeeze and back) so
// that the whole matrix of methods and tolerances runs in minutes.
#include <algorithm>
#include <cmath>
#include <limits>

#include "sphark/scenes/water_drop/water_drop.hpp"
#include "sphark/state/state_layout.hpp"
#include "sphark/study/study_scene.hpp"

namespace sphark {
namespace {

class DropProblem final : public StudyProblem {
 public:
  explicit DropProblem(const WaterDropConfig& config) : drop_(make_water_drop(config)) {}
  OdeSystem& system() override { return drop_.model->system(); }
  const std::vector<Real>& y0() const override { return drop_.y0; }
  std::vector<Real> absolute_tolerance(Real rtol) const override {
    return water_drop_absolute_tolerances(drop_, rtol);
  }
  Real energy(Real t, const Real* y) override { return drop_.model->diagnostics(t, y).total_energy; }

 private:
  WaterDrop drop_;
};

class DropScene final : public StudyScene {
 public:
  explicit DropScene(const StudySceneOptions& o) {
    config_.spacing = o.spacing > 0 ? o.spacing : 0.08;
    // CFL number 1 in max_stable_dt: the system's limit IS the CFL unit h / (c + |v|); the cap
    // of adaptive runs and the fixed steps are multiples of it.
    config_.cfl = 1.0;
    t_end_ = o.t_end > 0 ? o.t_end : 0.025;
    const int outputs = o.outputs > 0 ? o.outputs : 25;
    for (int k = 1; k <= outputs; ++k) times_.push_back(t_end_ * k / outputs);
    WaterDrop drop = make_water_drop(config_);
    particles_ = drop.particles();
    pos_offset_ = drop.model->layout().offset(Field::Position);
    cfl_unit_ = drop.model->system().max_stable_dt(0.0, drop.y0.data(), nullptr);
    for (Real t : times_) exact_.push_back(drop.exact.at(t));
    exact_model_ = std::move(drop.exact);
  }
  std::string name() const override { return "drop"; }
  std::string description() const override {
    return "water drop, " + std::to_string(particles_) + " particles (spacing " + std::to_string(config_.spacing) +
           "), t_end " + std::to_string(t_end_);
  }
  std::unique_ptr<StudyProblem> build() const override { return std::make_unique<DropProblem>(config_); }
  Real t_end() const override { return t_end_; }
  std::vector<Real> output_times() const override { return times_; }
  Real cfl_unit() const override { return cfl_unit_; }

  // Max relative semi-axis error against the exact ellipse (semi-axes 2 sqrt(<x^2>)).
  Real exact_error(Real t, const Real* y) const override {
    const SemiAxes ax = axes(y);
    const auto it = std::find_if(times_.begin(), times_.end(), [&](Real s) { return std::abs(s - t) <= 1e-12 * t_end_; });
    const EllipticDropState ex = it != times_.end() ? exact_[it - times_.begin()] : exact_model_.at(t);
    return std::max(std::abs(ax.x - ex.a) / ex.a, std::abs(ax.y - ex.b) / ex.b);
  }
  // Max relative semi-axis difference against the reference run's state.
  Real time_error(const Real* y, const Real* y_ref) const override {
    const SemiAxes a = axes(y), r = axes(y_ref);
    return std::max(std::abs(a.x - r.x) / r.x, std::abs(a.y - r.y) / r.y);
  }
  Real position_error(const Real* y, const Real* y_ref) const override {
    const std::size_t o = pos_offset_;
    Real sum = 0;
    for (std::size_t k = o; k < o + 2 * particles_; ++k) sum += (y[k] - y_ref[k]) * (y[k] - y_ref[k]);
    return std::sqrt(sum / static_cast<Real>(particles_)) / config_.radius;
  }
  std::string error_description() const override {
    return "max over output times of the relative semi-axis error (semi-axes 2 sqrt(<x^2>))";
  }

 private:
  SemiAxes axes(const Real* y) const { return measure_semi_axes(y + pos_offset_, particles_); }

  WaterDropConfig config_;
  Real t_end_ = 0;
  std::vector<Real> times_;
  std::size_t particles_ = 0;
  std::size_t pos_offset_ = 0;
  Real cfl_unit_ = 0;
  std::vector<EllipticDropState> exact_;
  EllipticDrop exact_model_{1.0, 0.0, 0.0};
};

}  // namespace

void register_water_drop_study_scenes(StudySceneRegistry& r) {
  r.push_back({"drop", [](const StudySceneOptions& o) -> std::unique_ptr<StudyScene> { return std::make_unique<DropScene>(o); }});
}

}  // namespace sphark
