#pragma once
// One water-drop run (cleaned or control) for the run driver: its system, diagnostics row, VTK
// frame, and the accuracy summary against the exact ellipse accumulated sample by sample.
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sphark/run/migration_step.hpp"
#include "sphark/run/scene.hpp"
#include "sphark/scenes/water_drop/distributed_drop.hpp"
#include "sphark/scenes/water_drop/water_drop.hpp"

namespace sphark {

struct DropRunSummary {
  TimeLoopResult loop;               // the run driver's outcome: status, reason, t reached, stats, ...
  std::size_t particles = 0;
  Real max_semi_axis_error = 0;      // max over samples of the relative semi-axis error
  Real time_of_max_error = 0;
  Real squeeze_error = 0;            // relative error of semi_axis_x at the first squeeze
  Real mean_abs_div_v_time_avg = 0;  // time average of the particle mean |div v|
  Real max_rel_density_error = 0;    // max over time
  Real kinetic_energy_end = 0;
  Real total_energy_drift = 0;       // (E(t_end) - E(0)) / E(0)
  long neighbour_builds = 0;
};

class DropRun final : public SceneRun {
 public:
  // diagnostics_every: the sampling interval (frames follow --output-every). A world with MPI:
  // a distributed run (DistributedDrop; migration every kMigrateEvery steps).
  DropRun(const WaterDropConfig& config, Real diagnostics_every, Real frame_every, Communicator world = {});

  OdeSystem& system() override { return drop_->model->system(); }
  const StateLayout& layout() const override { return drop_->model->layout(); }
  std::vector<Real> initial_state() override { return dist_ ? dist_->state() : drop_->y0; }
  StepperOptions stepper(const CoreOptions& core, std::string_view program) override;
  std::vector<std::string> columns() const override;
  std::vector<Real> diagnostics(Real t, const Real* y, const StepperStats& total) override;
  ParticleFrame frame(Real t, const Real* y) override;
  std::vector<std::pair<std::string, Real*>> saved_numbers() override;
  void settings(TimeLoopSettings& s) override;
  // Distributed: every kMigrateEvery steps the particles move to their RCB owners (the domains
  // recomputed every kRepartitionEvery steps).
  bool changes_particles() const override { return dist_ != nullptr; }
  std::optional<TimeLoopHooks::Resize> after_step(Real t, const Real* y,
                                                  const TimeLoopHooks::CarriedData& carried) override;
  static constexpr long kMigrateEvery = 50, kRepartitionEvery = 200;
  // Distributed: checkpoints of the whole drop, and a restart on any number of ranks takes this
  // rank's RCB domain of the checkpoint's positions (DistributedDrop::take_share).
  std::vector<std::int64_t> global_ids() const override;
  std::vector<std::int64_t> take_share(const Checkpoint& c) override;

  // The summary of the run (complete after the loop ended: pass its result).
  DropRunSummary summary(const TimeLoopResult& result) const;

 private:
  Communicator world_;
  std::unique_ptr<DistributedDrop> dist_;  // distributed runs
  std::optional<WaterDrop> serial_;        // serial runs
  WaterDrop* drop_;                        // the one of the two in use
  Real diagnostics_every_, frame_every_;
  Real atol_ = 0;    // of the stepper: the per-entry tolerances after a migration
  MigrationSchedule schedule_{kMigrateEvery, kRepartitionEvery};  // distributed (a restart: the checkpoint's steps)
  DropRunSummary sum_;
  // the numbers of the accuracy summary accumulated sample by sample (saved in checkpoints)
  Real samples_ = 0, e0_ = 0, div_integral_ = 0, t_prev_ = 0, div_prev_ = 0, prev_exact_a_ = 0, prev_err_x_ = 0,
       squeeze_seen_ = 0;
};

// The scene parameters as "key=value" lines (a restart must not change them).
std::string scene_text(const WaterDropConfig& c);

using DropResults = std::vector<std::pair<std::string, DropRunSummary>>;

// <out>/summary.csv (one row per run) and, per scheme with a cleaned and a control run, their
// ratios.
void write_drop_summary(const std::filesystem::path& out, const DropResults& results);
// Charts (paper Figs. 8-10 and the semi-axes against the exact ellipse) and rendered frames.
// Frames were written every frame_every up to t_end.
std::vector<PythonJob> drop_run_pictures(const std::filesystem::path& out, const std::string& label, Real frame_every,
                                         Real t_end);
void make_drop_pictures(const std::filesystem::path& out, const DropResults& results, const std::vector<std::string>& pending,
                        Real frame_every, Real t_end);
// "seed's WCSPH, cleaned", "delta-SPH, control": a run's label in legends, titles and summaries.
std::string run_legend(const std::string& run);

}  // namespace sphark
