#pragma once
// The one example driver: a time-integrating example is a Scene (its options, its runs and its
// report) handed to run_scene_main(). The driver does everything else the same way for every
// scene: the core options (--out, --t-end, --stepper, --rtol, ...) and the run-control options
// (--checkpoint-every, --restart, --inject-nan-at), --restart's stored options and its checks,
// the start-up (threads, --profile, the output directory, SIGINT/SIGTERM), each run through the
// shared time loop (run/time_loop.hpp: diagnostics CSV, VTK series, checkpoints, last good state
// on a failure), the report of how each run ended, and the exit code
// (0 ok, 2 bad options, 3 a run failed, 128 + signal when stopped, 1 any other error).
//
//   int main(int argc, char** argv) {
//     WaterDropScene scene;
//     return run_scene_main(scene, argc, argv);
//   }
//
// Order of calls: set_defaults(core) -> add_options(parser) -> (parse) -> check_options(parser,
// core, control, restarting) -> run_names() -> for each run: predicted_particles(name), make_probe_run(name,
// core, n) (the cost estimate: a run that does not fit in memory is refused here, exit 2, nothing
// written) -> (output directory, run.json) -> [run_instead(core)] -> for each: make_run(name, core) ->
// run_time_loop -> finished(name, run, result) -> report(core, runs, all_ok). A scene throws
// std::invalid_argument from make_probe_run / make_run for a value that only the scene can reject
// (one line, exit 2; from the probe, before anything is written).
//
// Signals: SIGINT/SIGTERM during a run end it within one RHS evaluation with a checkpoint; during
// the set-up of a run (make_run up to its stepper) a long loop's poll (throw_if_stop_requested)
// or, where no poll reaches, the set-up watchdog (run/signals.hpp) ends the program within
// ~0.3 s, with run.json saying "stopped" (there is no state to checkpoint yet).
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string_view>
#include <string>
#include <utility>
#include <vector>

#include "sphark/cli/options.hpp"
#include "sphark/integrate/ode_system.hpp"
#include "sphark/integrate/stepper_options.hpp"
#include "sphark/io/paraview_state.hpp"
#include "sphark/io/particle_frame.hpp"
#include "sphark/io/visualise.hpp"
#include "sphark/parallel/communicator.hpp"
#include "sphark/run/restart.hpp"
#include "sphark/run/time_loop.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark {

// One run of a scene (a variant: "cleaned", "cleaning", "mirror", ...): its system, its initial
// state and what it records. Owns the system and every buffer its frames point into.
class SceneRun {
 public:
  virtual ~SceneRun() = default;
  virtual OdeSystem& system() = 0;
  virtual const StateLayout& layout() const = 0;
  virtual std::vector<Real> initial_state() = 0;
  // The stepper of this run from the core options (default: stepper_options(core, system(),
  // program), which says so when ark-imex meets a run without a stiff part).
  // An empty `program`: quiet (the cost probe asks too).
  virtual StepperOptions stepper(const CoreOptions& core, std::string_view program);
  // The diagnostics row at (t, y) (its columns) and the VTK frame of (t, y), both functions of
  // (t, y): a frame's arrays stay valid until the next call.
  virtual std::vector<std::string> columns() const = 0;
  virtual std::vector<Real> diagnostics(Real t, const Real* y, const StepperStats& total) = 0;
  virtual ParticleFrame frame(Real t, const Real* y) = 0;
  // Optional early ends (see TimeLoopHooks::finished / root) and numbers kept in checkpoints.
  virtual bool finished(Real /*t*/) { return false; }
  virtual bool root(Real /*t*/, const std::vector<int>& /*found*/) { return false; }
  virtual std::vector<std::pair<std::string, Real*>> saved_numbers() { return {}; }
  // The stable step only falls as the run goes (a collapse): the steps and time the first line
  // predicts from the first step are lower bounds (printed ">=").
  virtual bool stable_step_falls() const { return false; }
  // A run whose particle set changes between steps (sink particles created, gas accreted): the
  // loop then steps one by one and calls after_step (TimeLoopHooks::after_step, restart_layout).
  virtual bool changes_particles() const { return false; }
  virtual std::optional<TimeLoopHooks::Resize> after_step(Real /*t*/, const Real* /*y*/,
                                                          const TimeLoopHooks::CarriedData& /*carried*/) {
    return std::nullopt;
  }
  virtual StateLayout restart_layout(const Checkpoint& /*c*/) { return layout(); }
  // With changes_particles: inside the top step of a stepper whose particles take steps of their
  // own, the particles removed at an event from those active there (TimeLoopHooks::remove_active,
  // with entry_source), and the particles of a layout given back (restore_particles).
  virtual std::optional<TimeLoopHooks::Resize> remove_active(Real /*t*/, const Real* /*y*/,
                                                             const std::vector<std::size_t>& /*active*/) {
    return std::nullopt;
  }
  virtual void restore_particles(const StateLayout& /*layout*/) {}
  // The particles that must end their steps at the next event (TimeLoopHooks::wake_next).
  virtual std::vector<std::size_t> wake_next(Real /*t*/, const Real* /*y*/, const std::vector<std::size_t>& /*active*/) {
    return {};
  }
  // A distributed run (Scene::supports_distributed_runs): the global ids of this rank's particles
  // in state order, and on a restart this rank's share of the checkpoint's particles, which the
  // system then holds (TimeLoopHooks::global_ids, take_share).
  virtual std::vector<std::int64_t> global_ids() const;
  virtual std::vector<std::int64_t> take_share(const Checkpoint& c);
  // Where and how often it writes: the driver fills `s` (program, run, options, scene text,
  // t_end, sample/frame intervals from --output-every, <dir>/diagnostics.csv, <dir>/<name>_NNNNN.vtp,
  // <dir>/checkpoint.bin, run control) before this call; a scene changes what differs.
  virtual void settings(TimeLoopSettings& /*s*/) {}
};

class Scene {
 public:
  virtual ~Scene() = default;
  virtual std::string program() const = 0;      // "water_drop": binary, checkpoint owner, messages
  virtual std::string description() const = 0;  // the first line of --help
  // The scene's defaults of the core options (out, t_end, stepper, tolerances, output_every).
  virtual void set_defaults(CoreOptions& core) = 0;
  // --stepper names this scene accepts (default: every core stepper).
  virtual std::vector<std::string> stepper_names() const;
  // Where checkpoints go, for --help ("<out>/<run>/checkpoint.bin").
  virtual std::string checkpoint_help() const { return "<out>/<run>/checkpoint.bin"; }
  virtual void add_options(OptionParser& p) = 0;
  // Checks across options after parsing (p.fail: one line, exit 2, nothing written); may complete
  // core options whose default depends on the scene's (e.g. --output-every of a case).
  virtual void check_options(const OptionParser& /*p*/, CoreOptions& /*core*/, const RunControlOptions& /*control*/,
                             bool /*restarting*/) {}
  // A case that is not a sequence of time-loop runs (e.g. an ensemble of short runs): its exit
  // code, or nullopt to go on with run_names(). Called after the start-up.
  virtual std::optional<int> run_instead(const CoreOptions& /*core*/) { return std::nullopt; }
  // The unit, in the system's time, of the time options (--t-end, --output-every, --dt,
  // --checkpoint-every, --inject-nan-at): 1, or a scene's natural time (the collapse's free-fall
  // time). Asked after check_options(), whose checks see the options as given.
  virtual Real time_unit() const { return 1; }
  // The runs the options ask for, in order; each gets <out>/<subdirectory(name)>.
  virtual std::vector<std::string> run_names() const = 0;
  // --restart continues the checkpoint's run alone; a scene names the option that contradicts it
  // (p.fail). Default: the run must be one of run_names().
  virtual void check_restart_run(const OptionParser& p, const std::string& checkpoint_run) const;
  virtual std::filesystem::path subdirectory(const std::string& run) const { return run; }
  // The scene's parameters of a run as "key=value" lines: stored in its checkpoints, and a
  // restart must give the same text.
  virtual std::string scene_text(const std::string& run) const = 0;
  // With --concurrent-runs > 1, make_run and the runs it makes are used from several threads at
  // once (one run each): make_run must not change the scene; finished() is called on one thread
  // at a time, in the order of run_names().
  virtual std::unique_ptr<SceneRun> make_run(const std::string& run, const CoreOptions& core) = 0;
  // The default of --concurrent-runs: 1, or more for a scene whose runs are small enough that
  // side by side, each on fewer threads, they end sooner than one after the other (measured).
  virtual int concurrent_runs() const { return 1; }
  // The cost estimate (run/cost_estimate.hpp), before anything is built or written: the particles
  // of `run` from the options alone (a real number: options can ask for more than any machine
  // holds; NaN: unknown, then no estimate), the option that sets them (named by a refusal), and
  // the same run with about `particles` particles, every other option unchanged (nullptr: no
  // probe). A probe must write nothing; its frame() is never called.
  virtual Real predicted_particles(const std::string& /*run*/) const;
  virtual std::string size_option() const { return {}; }
  virtual std::unique_ptr<SceneRun> make_probe_run(const std::string& /*run*/, const CoreOptions& /*core*/,
                                                   Real /*particles*/) {
    return nullptr;
  }
  // After each run (also a failed or stopped one), and once at the end of all (or after the first
  // run that did not end ok) with the runs planned (all of run_names(), or a restart's one):
  // summaries and pictures. report() returns an exit code (non-zero if writing the report
  // failed); the driver returns the runs' code if that is not 0, else report()'s.
  virtual void finished(const std::string& /*run*/, SceneRun& /*r*/, const TimeLoopResult& /*result*/) {}
  virtual int report(const CoreOptions& /*core*/, const std::vector<std::string>& /*runs*/, bool /*all_ok*/) {
    return 0;
  }
  // The ParaView views of the runs done (paraview --state=<file>): state files relative to <out>,
  // each with its views (series relative to the state file's folder). The driver writes them at
  // the end, with the scene's natural colouring; a view that cannot be written is a warning.
  struct ParaViewStateFile {
    std::filesystem::path file;
    std::vector<ParaViewView> views;
  };
  virtual std::vector<ParaViewStateFile> paraview_states(const std::vector<std::string>& /*runs_done*/) const {
    return {};
  }
  // The pictures of one run alone (its frames, its curves against an exact solution), once it
  // has ended well and finished() has seen it. With --concurrent-runs, a lane that has no run
  // left to start draws them there (one Python process) while the other runs go on; report()
  // draws those still pending (run_pictures_pending), with its comparisons.
  virtual std::vector<PythonJob> run_pictures(const std::string& /*run*/, const CoreOptions& /*core*/) const {
    return {};
  }
  bool run_pictures_pending(const std::string& run) const { return run_pictures_drawn_.count(run) == 0; }
  void set_run_pictures_drawn(const std::string& run) { run_pictures_drawn_.insert(run); }  // by the driver

  // Distributed runs (mpirun, docs/scaling.md): a scene that supports them builds its runs on
  // world() (set by run_scene_main before the options are parsed; serial otherwise), with the
  // stepper's communicator, particle ids in its frames and diagnostics reduced over the ranks.
  virtual bool supports_distributed_runs() const { return false; }
  const Communicator& world() const { return world_; }
  void set_world(Communicator world) { world_ = std::move(world); }

 private:
  Communicator world_;
  std::set<std::string> run_pictures_drawn_;
};

// Parses the options, runs the scene and returns the exit code (see the top of this file).
int run_scene_main(Scene& scene, int argc, char** argv);
// The same on the ranks of `world` (every rank calls it; MpiSession::run around it): rank 0
// prints and writes run.json and the CSVs, every rank its frames' pieces. A scene without
// supports_distributed_runs(), --checkpoint-every and --restart are refused on > 1 rank (exit 2).
int run_scene_main(Scene& scene, int argc, char** argv, const Communicator& world);

}  // namespace sphark
