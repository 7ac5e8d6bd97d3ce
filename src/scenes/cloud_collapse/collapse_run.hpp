#pragma once
// One run of the cloud collapse (a variant) for the run driver: the system, its diagnostics row,
// its frames (gas and sinks), the sink events between steps, the step-level record, and the
// column-density maps of its last frame. Private to src/scenes/cloud_collapse.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sphark/diagnostics/spmhd_diagnostics.hpp"
#include "sphark/run/scene.hpp"
#include "sphark/scenes/cloud_collapse/cloud_collapse.hpp"
#include "sphark/sinks/sink_run.hpp"

namespace sphark {

class CollapseRun final : public SceneRun {
 public:
  CollapseRun(const CloudCollapseParams& p, Real diagnostics_every);
  OdeSystem& system() override { return cloud_.scheme; }
  const StateLayout& layout() const override { return cloud_.scheme.layout(); }
  std::vector<Real> initial_state() override { return cloud_.y0; }
  std::vector<std::string> columns() const override;
  std::vector<Real> diagnostics(Real t, const Real* y, const StepperStats& st) override;
  ParticleFrame frame(Real t, const Real* y) override;
  std::vector<std::pair<std::string, Real*>> saved_numbers() override;
  bool changes_particles() const override { return true; }
  bool stable_step_falls() const override { return true; }  // the densest gas's step, to the sink
  std::optional<TimeLoopHooks::Resize> after_step(Real t, const Real* y,
                                                  const TimeLoopHooks::CarriedData& carried) override;
  StateLayout restart_layout(const Checkpoint& c) override;
  std::optional<TimeLoopHooks::Resize> remove_active(Real t, const Real* y, const std::vector<std::size_t>& active) override;
  void restore_particles(const StateLayout& layout) override { sinks_.restore_particles(cloud_.scheme, layout); }
  std::vector<std::size_t> wake_next(Real, const Real* y, const std::vector<std::size_t>& active) override {
    return sinks_.wake_next(cloud_.scheme, y, active);
  }
  void settings(TimeLoopSettings& s) override;

  // After the run: the step levels and the column-density maps of the last frame (its state).
  void write_final_products();
  const CloudCollapse& cloud() const { return cloud_; }
  const SinkEventLog& sink_log() const { return sinks_.log(); }
  // The first sink against the gas denser than fraction_of_max x the densest at the last frame
  // (the disc): its distance from that gas's centre of mass and its speed relative to it (code
  // units); NaN without a sink.
  std::pair<Real, Real> sink_offset(Real fraction_of_max);

 private:
  void write_step_levels(const std::string& event, Real t, const Real* y);
  void announce_creation(Real t, const std::optional<TimeLoopHooks::Resize>& r);  // message, step levels
  void write_maps(const Real* y);

  CloudCollapseParams p_;
  CloudCollapse cloud_;
  Real every_;
  std::filesystem::path dir_;
  SpmhdFrame frame_;
  SinkRunSupport sinks_;  // the sink events, their checkpointed log, the restart's layout
  long forced_announced_ = 0;  // forced creations announced so far
  std::vector<Real> last_frame_y_;  // the state of the last frame written
  Real last_frame_t_ = 0;
  std::string levels_csv_;  // step_levels.csv so far
};

// The run's summary_<variant>.csv text (header + one line; collapse_report.cpp).
std::string collapse_summary(const std::string& variant, CollapseRun& run, const TimeLoopResult& result);

}  // namespace sphark
