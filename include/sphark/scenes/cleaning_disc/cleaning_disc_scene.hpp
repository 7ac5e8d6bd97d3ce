#pragma once
// The cleaning-disc example (seed 000 §IV-A, Fig. 1) for the run driver (run/scene.hpp): the four
// runs of cleaning_disc_variants() in turn, summary.csv and Fig. 1.
#include <string>
#include <vector>

#include "sphark/run/scene.hpp"
#include "sphark/scenes/cleaning_disc/cleaning_disc.hpp"

namespace sphark {

class CleaningDiscScene final : public Scene {
 public:
  std::string program() const override { return "cleaning_disc"; }
  std::string description() const override;
  void set_defaults(CoreOptions& core) override;
  std::vector<std::string> stepper_names() const override;
  std::string checkpoint_help() const override { return "<out>/<run>.checkpoint.bin"; }
  void add_options(OptionParser& p) override;
  void check_options(const OptionParser& p, CoreOptions& core, const RunControlOptions& control,
                     bool restarting) override;
  std::vector<std::string> run_names() const override;
  std::filesystem::path subdirectory(const std::string&) const override { return {}; }  // all in <out>
  void check_restart_run(const OptionParser& p, const std::string& checkpoint_run) const override;
  std::string scene_text(const std::string& run) const override;
  std::unique_ptr<SceneRun> make_run(const std::string& run, const CoreOptions& core) override;
  Real predicted_particles(const std::string& run) const override;
  std::string size_option() const override { return "--spacing"; }
  std::unique_ptr<SceneRun> make_probe_run(const std::string& run, const CoreOptions& core, Real particles) override;
  void finished(const std::string& run, SceneRun& r, const TimeLoopResult& result) override;
  int report(const CoreOptions& core, const std::vector<std::string>& runs, bool all_ok) override;
  std::vector<ParaViewStateFile> paraview_states(const std::vector<std::string>& runs_done) const override;
  bool supports_distributed_runs() const override { return true; }  // mpirun: SpmhdScheme::distribute

  struct Summary {
    std::string name;
    Real initial_max = 0, final_max = 0, peak_max = 0;
    Real growth_rate = 0;  // least-squares slope of ln(max h|div B|/B0), see summarise()
    Real blew_up_at = -1;  // time at which the cleaning energy exceeded kBlowUp times its start
    Real energy_change = 0;
    TimeLoopResult loop;
  };

 private:
  const CleaningDiscVariant& variant(const std::string& name) const;

  Real sigma_ = 0.3, spacing_ = 0.04;
  std::string which_ = "all";
  Real t_end_ = 0;
  std::vector<Summary> results_;
};

}  // namespace sphark
