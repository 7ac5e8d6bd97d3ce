#pragma once
// One run of the gravitating sphere for the run driver (run/scene.hpp): its system, its
// diagnostics row (energies, momentum, angular momentum, maximum density, the Lagrangian radii
// against the exact free fall, the sink columns), its frames (gas, and the sinks as points) and,
// with sinks, the sink events between steps (sinks/sink_run.hpp, shared with the cloud collapse).
#include <optional>
#include <string>
#include <vector>

#include "sphark/diagnostics/spmhd_diagnostics.hpp"
#include "sphark/run/scene.hpp"
#include "sphark/scenes/gravitating_sphere/gravitating_sphere.hpp"
#include "sphark/sinks/sink_run.hpp"

namespace sphark {

class GravitatingSphereRun final : public SceneRun {
 public:
  GravitatingSphereRun(const GravitatingSphereParams& p, Real diagnostics_every);
  OdeSystem& system() override { return sphere_.scheme; }
  const StateLayout& layout() const override { return sphere_.scheme.layout(); }
  std::vector<Real> initial_state() override { return sphere_.y0; }
  // t, energies, momentum, angular_momentum_z (gas and sinks, with spins), max_density (gas), the
  // Lagrangian radii of 10/50/90 % of the gas + sink mass about its centre of mass, the exact free
  // fall's radii (uniform, until t_ff), n_sinks, sink_mass, rhs_evals, steps.
  std::vector<std::string> columns() const override;
  std::vector<Real> diagnostics(Real t, const Real* y, const StepperStats& st) override;
  ParticleFrame frame(Real t, const Real* y) override { return frame_.build(sphere_.scheme, t, y); }
  void settings(TimeLoopSettings& s) override;
  // With sinks: ends the run (normally, after the sample at t) once an event would have taken
  // every gas particle (SinkEventLog::gas_exhausted; the cold collapse ends on its sink at t_ff).
  bool finished(Real t) override;
  // Sinks (only with GravitatingSphereParams::sinks: without, the run steps as before, advance()).
  bool changes_particles() const override { return p_.sinks; }
  std::vector<std::pair<std::string, Real*>> saved_numbers() override;
  std::optional<TimeLoopHooks::Resize> after_step(Real t, const Real* y,
                                                  const TimeLoopHooks::CarriedData& carried) override;
  StateLayout restart_layout(const Checkpoint& c) override;
  std::optional<TimeLoopHooks::Resize> remove_active(Real t, const Real* y, const std::vector<std::size_t>& active) override;
  void restore_particles(const StateLayout& layout) override { sinks_.restore_particles(sphere_.scheme, layout); }
  std::vector<std::size_t> wake_next(Real, const Real* y, const std::vector<std::size_t>& active) override {
    return sinks_.wake_next(sphere_.scheme, y, active);
  }

  GravitatingSphere& sphere() { return sphere_; }
  const SinkEventLog& sink_log() const { return sinks_.log(); }

 private:
  void announce_creation(Real t) const;  // the message when the last event created a sink
  GravitatingSphereParams p_;
  GravitatingSphere sphere_;
  Real every_;
  std::vector<Real> r0_;  // the Lagrangian radii at t = 0
  SpmhdFrame frame_;
  SinkRunSupport sinks_;
};

// The Lagrangian radii (kSphereFractions) of state y: of the gas alone (equal masses) without a
// sink, else of the gas and the sinks as point masses.
std::vector<Real> sphere_lagrangian_radii(const SpmhdScheme<3>& scheme, const Real* y);
extern const std::vector<Real> kSphereFractions;  // 0.1, 0.5, 0.9

}  // namespace sphark
