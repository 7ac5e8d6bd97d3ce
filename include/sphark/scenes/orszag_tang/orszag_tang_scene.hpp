#pragma once
// The Orszag-Tang example (seed 000 §IV-B, Figs. 2-3) for the run driver (run/scene.hpp): the
// five div B control variants one after the other, summary.csv and the figures.
#include <string>
#include <vector>

#include "sphark/run/scene.hpp"
#include "sphark/scenes/orszag_tang/orszag_tang.hpp"

namespace sphark {

class OrszagTangScene final : public Scene {
 public:
  std::string program() const override { return "orszag_tang"; }
  std::string description() const override;
  void set_defaults(CoreOptions& core) override;
  std::vector<std::string> stepper_names() const override;
  std::string checkpoint_help() const override { return "<out>/<variant>/checkpoint.bin"; }
  void add_options(OptionParser& p) override;
  // Under mpirun: Euler potentials (and "all", which includes them) are refused (not distributed).
  void check_options(const OptionParser& p, CoreOptions& core, const RunControlOptions& control,
                     bool restarting) override;
  bool supports_distributed_runs() const override { return true; }  // mpirun: SpmhdScheme::distribute
  std::vector<std::string> run_names() const override;
  std::filesystem::path subdirectory(const std::string& run) const override;
  void check_restart_run(const OptionParser& p, const std::string& checkpoint_run) const override;
  std::string scene_text(const std::string& run) const override;
  std::unique_ptr<SceneRun> make_run(const std::string& run, const CoreOptions& core) override;
  Real predicted_particles(const std::string& run) const override;
  std::string size_option() const override { return "--nx"; }
  std::unique_ptr<SceneRun> make_probe_run(const std::string& run, const CoreOptions& core, Real particles) override;
  void finished(const std::string& run, SceneRun& r, const TimeLoopResult& result) override;
  int report(const CoreOptions& core, const std::vector<std::string>& runs, bool all_ok) override;
  std::vector<ParaViewStateFile> paraview_states(const std::vector<std::string>& runs_done) const override;

  struct Summary {
    std::string variant;
    Real mean_at_end = 0, max_at_end = 0, mean_at_half = 0, energy_change = 0, momentum = 0;
    TimeLoopResult loop;
  };

 private:
  OrszagTangParams params_;
  std::string variant_ = "all";
  std::vector<Summary> results_;
};

}  // namespace sphark
