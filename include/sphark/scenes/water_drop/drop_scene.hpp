#pragma once
// The oscillating elliptic water drop of seed 000, §IV-D as an example for the run driver
// (run/scene.hpp): WCSPH with constrained velocity cleaning ("cleaned") and without it
// ("control"), each against the exact ellipse, in two schemes: the seed's plain WCSPH (runs
// "seed_cleaned", "seed_control": the seed's cleaning comparison, Figs. 8-10) and delta-SPH
// (runs "cleaned", "control": the accurate one against the ellipse); a summary table, the
// paper's Figs. 8-10 and rendered frames.
#include <string>
#include <utility>
#include <vector>

#include "sphark/run/scene.hpp"
#include "sphark/scenes/water_drop/water_drop.hpp"

namespace sphark {

struct DropRunSummary;

class WaterDropScene final : public Scene {
 public:
  WaterDropScene();
  ~WaterDropScene() override;
  std::string program() const override { return "water_drop"; }
  std::string description() const override;
  bool supports_distributed_runs() const override { return true; }  // mpirun: DistributedDrop
  void set_defaults(CoreOptions& core) override;
  void add_options(OptionParser& p) override;
  void check_options(const OptionParser& p, CoreOptions& core, const RunControlOptions& control,
                     bool restarting) override;
  std::vector<std::string> run_names() const override;
  void check_restart_run(const OptionParser& p, const std::string& checkpoint_run) const override;
  std::string scene_text(const std::string& run) const override;
  std::unique_ptr<SceneRun> make_run(const std::string& run, const CoreOptions& core) override;
  // Two runs at a time, one thread each: a 1,976-particle run gains 1.2x from a second thread
  // (docs/water_drop.md, "Time of the main job").
  int concurrent_runs() const override { return 2; }
  Real predicted_particles(const std::string& run) const override;
  std::string size_option() const override { return "--spacing"; }
  std::unique_ptr<SceneRun> make_probe_run(const std::string& run, const CoreOptions& core, Real particles) override;
  void finished(const std::string& run, SceneRun& r, const TimeLoopResult& result) override;
  int report(const CoreOptions& core, const std::vector<std::string>& runs, bool all_ok) override;
  // A run's semi-axes against the exact ellipse and its frames (the comparisons: report()).
  std::vector<PythonJob> run_pictures(const std::string& run, const CoreOptions& core) const override;
  std::vector<ParaViewStateFile> paraview_states(const std::vector<std::string>& runs_done) const override;

 private:
  WaterDropConfig config_of(const std::string& run) const;

  WaterDropConfig config_;
  std::string scheme_ = "both", cleaning_ = "both", initial_pressure_ = "exact";
  Real diagnostics_every_ = 1e-4;
  std::vector<std::pair<std::string, DropRunSummary>> results_;
};

}  // namespace sphark
