#pragma once
// The cloud-collapse example (seed 000 §IV-C, Figs. 4-6; issue #16) for the run driver
// (run/scene.hpp). One run per --variant (none | cleaning | cleaning+resistivity, or "both": the
// default cleaned variant, cleaning+resistivity, then none); each writes
// <out>/<variant>/diagnostics.csv (the columns plus the step-size record), the VTK
// series (gas and sinks), step_levels.csv (the particles' own stable steps on power-of-two
// levels when the sink forms and at the end), column-density maps along y
// (the whole cloud and a zoom on the sink) and sinks.csv (creation and accretion); the report
// draws the figures from every variant present under <out> (vis/cloud_collapse.py).
// summary_<variant>.csv per run: the sink's formation time (t_ff), the peaks of density, of mean
// h|div B|/|B| and of |momentum|, the sink's offset from the dense gas at the end, the sink
// checks' refusals, the cost (steps, RHS evaluations, wall time).
//
// Times: --t-end, --output-every, --diagnostics-every and --checkpoint-every are in units of the
// free-fall time t_ff here (the only scene where they are not in code time).
#include <memory>
#include <string>
#include <vector>

#include "sphark/run/scene.hpp"
#include "sphark/scenes/cloud_collapse/cloud_collapse.hpp"

namespace sphark {

class CloudCollapseScene final : public Scene {
 public:
  std::string program() const override { return "cloud_collapse"; }
  std::string description() const override;
  void set_defaults(CoreOptions& core) override;
  void add_options(OptionParser& p) override;
  void check_options(const OptionParser& p, CoreOptions& core, const RunControlOptions& control,
                     bool restarting) override;
  Real time_unit() const override;  // t_ff
  std::vector<std::string> run_names() const override;
  void check_restart_run(const OptionParser& p, const std::string& checkpoint_run) const override;
  std::filesystem::path subdirectory(const std::string& run) const override;
  std::string scene_text(const std::string& run) const override;
  std::unique_ptr<SceneRun> make_run(const std::string& run, const CoreOptions& core) override;
  Real predicted_particles(const std::string& run) const override;  // sphere and ambient
  std::string size_option() const override { return "--particles"; }
  std::unique_ptr<SceneRun> make_probe_run(const std::string& run, const CoreOptions& core, Real particles) override;
  void finished(const std::string& run, SceneRun& r, const TimeLoopResult& result) override;
  int report(const CoreOptions& core, const std::vector<std::string>& runs, bool all_ok) override;
  std::vector<ParaViewStateFile> paraview_states(const std::vector<std::string>& runs_done) const override;

 private:
  CloudCollapseParams params_;
  std::string variant_ = "cleaning+resistivity";  // CloudCollapseParams::variant's default
  std::string gravity_ = "tree";
  std::string opening_ = "fixed";
  std::string subset_density_ = "predicted";
  long particles_ = static_cast<long>(CloudCollapseParams{}.particles);
  bool local_ch_ = false, no_tensile_correction_ = false;
  Real diagnostics_every_ = 0.005;  // t_ff
  Real free_fall_time_ = 0;         // code units, from the parameters
  std::vector<std::pair<std::string, std::string>> summaries_;  // (variant, summary.csv line) of the runs done
};

}  // namespace sphark
