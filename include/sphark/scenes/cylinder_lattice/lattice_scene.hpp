#pragma once
// The cylinder-lattice example (seed 004, §8) for the run driver (run/scene.hpp): a single run,
// the medium-resolution comparison of the ghost maps (§8.1, Fig. 9), or the low-resolution
// ensemble of t_max = min{t_final, t_penetration, t_accumulation} (§8.2, eq. 37, Fig. 10).
#include <string>
#include <vector>

#include "sphark/run/scene.hpp"
#include "sphark/scenes/cylinder_lattice/lattice_run.hpp"

namespace sphark {

class CylinderLatticeScene final : public Scene {
 public:
  CylinderLatticeScene();
  std::string program() const override { return "cylinder_lattice"; }
  std::string description() const override;
  void set_defaults(CoreOptions& core) override;
  // One step for every particle: the ghost scheme evaluates no particle subsets and the run has
  // root functions (its particles' own steps lie on one level: docs/time_integration.md).
  std::vector<std::string> stepper_names() const override { return global_stepper_names(); }
  std::string checkpoint_help() const override {
    return "<out>/single_<map>/ or <out>/<map>/checkpoint.bin (single, medium)";
  }
  void add_options(OptionParser& p) override;
  void check_options(const OptionParser& p, CoreOptions& core, const RunControlOptions& control,
                     bool restarting) override;
  std::optional<int> run_instead(const CoreOptions& core) override;
  std::vector<std::string> run_names() const override { return maps_; }
  std::filesystem::path subdirectory(const std::string& map) const override;
  void check_restart_run(const OptionParser& p, const std::string& checkpoint_run) const override;
  std::string scene_text(const std::string& map) const override;
  std::unique_ptr<SceneRun> make_run(const std::string& map, const CoreOptions& core) override;
  Real predicted_particles(const std::string&) const override { return static_cast<Real>(run_.particles); }
  std::string size_option() const override { return "--particles"; }
  std::unique_ptr<SceneRun> make_probe_run(const std::string& map, const CoreOptions& core, Real particles) override;
  void finished(const std::string& map, SceneRun& r, const TimeLoopResult& result) override;
  int report(const CoreOptions& core, const std::vector<std::string>& runs, bool all_ok) override;
  std::vector<ParaViewStateFile> paraview_states(const std::vector<std::string>& runs_done) const override;
  // Under mpirun: single and medium (the ensemble's many small runs are serial only).
  bool supports_distributed_runs() const override { return true; }

  struct Outcome {
    std::string map;
    LatticeRunResult result;
    double wall_seconds = 0;
  };

 private:
  LatticeRunConfig run_;            // params (map, v0, ...), particles, seed, t_end, stepper
  std::vector<std::string> maps_;   // "mirror", "nonlinear"
  std::vector<Real> v0s_;           // ensemble
  int seeds_ = 20;                  // ensemble: seeds 1..seeds
  std::string case_ = "single", bc_ = "free-slip", map_ = "default", stepper_;
  long particles_ = 0, seed_ = 1;
  // --cfl 0 (the default): the case's CFL number. The ensemble's 600 runs give Fig. 10's outcomes
  // at 0.4 as at 0.25 (4 of 600 differ from CFL 0.125 at each) for 0.68x the CPU; the medium
  // run keeps 0.25 (at 0.4 the nonlinear map's time-mean v_y field moves by 0.128 of rms v_y,
  // more than the two maps differ at 0.25, 0.079; docs/time_integration.md).
  static constexpr Real kEnsembleCfl = 0.4, kResolvedCfl = 0.25;
  Real cfl_ = 0;
  std::vector<Outcome> outcomes_;
};

}  // namespace sphark
