#pragma once
// The gravitating-sphere example (issue #15) for the run driver (run/scene.hpp): the cold uniform
// collapse against the exact free fall of every shell, or the Evrard collapse; diagnostics.csv
// (energies, momentum, angular momentum, maximum density, Lagrangian radii), summary.csv, charts.
#include <string>
#include <vector>

#include "sphark/run/scene.hpp"
#include "sphark/scenes/gravitating_sphere/gravitating_sphere.hpp"

namespace sphark {

class GravitatingSphereScene final : public Scene {
 public:
  std::string program() const override { return "gravitating_sphere"; }
  std::string description() const override;
  void set_defaults(CoreOptions& core) override;
  void add_options(OptionParser& p) override;
  void check_options(const OptionParser& p, CoreOptions& core, const RunControlOptions& control,
                     bool restarting) override;
  std::vector<std::string> run_names() const override { return {params_.profile}; }
  std::string scene_text(const std::string& run) const override;
  std::unique_ptr<SceneRun> make_run(const std::string& run, const CoreOptions& core) override;
  Real predicted_particles(const std::string&) const override { return static_cast<Real>(params_.particles); }
  std::string size_option() const override { return "--particles"; }
  std::unique_ptr<SceneRun> make_probe_run(const std::string& run, const CoreOptions& core, Real particles) override;
  void finished(const std::string& run, SceneRun& r, const TimeLoopResult& result) override;
  int report(const CoreOptions& core, const std::vector<std::string>& runs, bool all_ok) override;
  std::vector<ParaViewStateFile> paraview_states(const std::vector<std::string>& runs_done) const override;

 private:
  GravitatingSphereParams params_;
  std::string gravity_ = "tree";
  std::string opening_ = "fixed";
  std::string sinks_ = "off";
  long particles_ = 30000;
  Real diagnostics_every_ = 0.01;
  std::vector<TimeLoopResult> results_;
};

}  // namespace sphark
