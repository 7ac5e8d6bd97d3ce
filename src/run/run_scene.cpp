// run_scene_main: the one driver of every time-integrating example (run/scene.hpp).
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <exception>
#include <functional>
#include <optional>
#include <stdexcept>

#include <map>
#include <mutex>
#include <utility>

#include "scene_cost.hpp"
#include "sphark/cli/run_record.hpp"
#include "sphark/integrate/stepper.hpp"
#include "sphark/parallel/mpi_session.hpp"
#include "sphark/run/concurrent_jobs.hpp"
#include "sphark/run/restart.hpp"
#include "sphark/run/scene.hpp"
#include "sphark/run/signals.hpp"

namespace sphark {

StepperOptions SceneRun::stepper(const CoreOptions& core, std::string_view program) {
  return stepper_options(core, system(), program);
}

std::vector<std::int64_t> SceneRun::global_ids() const {
  throw std::logic_error("this run is not distributed: no global ids");
}

std::vector<std::int64_t> SceneRun::take_share(const Checkpoint&) {
  throw std::logic_error("this run is not distributed: it takes no share of a checkpoint");
}

std::vector<std::string> Scene::stepper_names() const { return core_stepper_names(); }

void Scene::check_restart_run(const OptionParser& p, const std::string& checkpoint_run) const {
  const std::vector<std::string> runs = run_names();
  if (std::find(runs.begin(), runs.end(), checkpoint_run) != runs.end()) return;
  std::string listed;
  for (const auto& r : runs) listed += (listed.empty() ? "" : ", ") + r;
  p.fail("--restart", "the checkpoint's run '" + checkpoint_run + "' is not among the runs these options ask for (" +
                          listed + ")");
}

namespace {

struct ParsedRun {
  explicit ParsedRun(const Scene& scene) : parser(scene.program(), scene.description()) {}
  OptionParser parser;  // kept: the run record lists its every option
  CoreOptions core;
  RunControlOptions control;
  std::vector<std::string> runs;
  std::vector<std::string> stored_options;  // argv[1..] of this run (a restart's stored ones first)
  Json given_values;  // every option's value as given, times in the scene's unit (run.json)
  std::map<std::string, detail::PlannedCost> costs;  // per run: its probe (cost estimate)
};

// The time options, given in the scene's time unit, in the system's time.
void in_system_time(Real unit, CoreOptions& core, RunControlOptions& control) {
  if (unit == 1) return;
  core.t_end *= unit;
  core.output_every *= unit;
  core.dt *= unit;
  core.max_dt *= unit;
  control.checkpoint_every *= unit;
  control.inject_nan_at *= unit;
}

void parse(ParsedRun& r, Scene& scene, int argc, char** argv, const Checkpoint* restart) {
  const std::vector<std::string> args = run_arguments(scene.program(), argc, argv, restart);
  OptionParser& parser = r.parser;
  scene.set_defaults(r.core);
  add_core_options(parser, r.core, scene.stepper_names());
  scene.add_options(parser);
  r.control.concurrent_runs = scene.concurrent_runs();
  add_run_options(parser, r.control, scene.checkpoint_help());
  const std::vector<const char*> parse_argv = as_argv(args);
  parser.parse_or_exit(static_cast<int>(parse_argv.size()), parse_argv.data());
  check_run_options(parser, r.control, r.core);
  scene.check_options(parser, r.core, r.control, restart != nullptr);
  r.given_values = parser.to_json();
  in_system_time(scene.time_unit(), r.core, r.control);
  r.runs = scene.run_names();
  if (restart) {  // one run: the checkpoint's
    const std::string name = restart->text("run");
    scene.check_restart_run(parser, name);
    r.runs = {name};
    check_restart_text(parser, *restart, "scene", scene.scene_text(name), "scene parameters");
    check_restart_t_end(parser, *restart, r.core.t_end);
  }
  r.stored_options.assign(args.begin() + 1, args.end());
  r.core.threads = apply_thread_count(r.core.threads, scene.program());  // the probes run on the run's threads
  r.given_values["threads"] = r.core.threads;  // (the record names the threads the run took)
  install_stop_handlers();  // a probe stops at a request; run_scene_main then ends the set-up
  for (const std::string& name : r.runs)
    if (stop_requested() == 0) r.costs[name] = detail::plan_cost(scene, name, r.core, parser);
}

TimeLoopSettings default_settings(const Scene& scene, const std::string& name, const ParsedRun& p,
                                  const std::filesystem::path& dir, const Checkpoint* restart, SceneRun& run) {
  TimeLoopSettings ts;
  ts.program = scene.program();
  ts.run = name;
  ts.argv = p.stored_options;
  ts.texts = {{"scene", scene.scene_text(name)}};
  ts.t_end = p.core.t_end;
  ts.sample_every = p.core.output_every > 0 ? p.core.output_every : p.core.t_end;  // 0: first and last only
  ts.diagnostics_csv = dir / "diagnostics.csv";
  ts.columns = run.columns();
  ts.frames_dir = dir;
  ts.frames_basename = scene.program();
  ts.frame_every = ts.sample_every;
  apply_run_control(ts, p.control, restart, dir / "checkpoint.bin");
  return ts;
}

// One run's arming of the set-up watchdog: armed from construction until end() (the time loop
// started) or destruction (the set-up threw), whichever comes first; once.
class SetupArming {
 public:
  explicit SetupArming(SetupWatchdog& w) : watchdog_(w) { watchdog_.arm(); }
  ~SetupArming() { end(); }
  SetupArming(const SetupArming&) = delete;
  SetupArming& operator=(const SetupArming&) = delete;
  void end() {
    if (armed_) watchdog_.disarm();
    armed_ = false;
  }

 private:
  SetupWatchdog& watchdog_;
  bool armed_ = true;
};

TimeLoopHooks hooks_of(SceneRun& run, SetupArming& arming, bool distributed) {
  TimeLoopHooks h;
  h.started = [&arming] { arming.end(); };  // the set-up is over: a stop now gets a checkpoint
  h.diagnostics = [&run](Real t, const Real* y, const StepperStats& st) { return run.diagnostics(t, y, st); };
  h.frame = [&run](Real t, const Real* y) { return run.frame(t, y); };
  h.finished = [&run](Real t) { return run.finished(t); };
  h.root = [&run](Real t, const std::vector<int>& found) { return run.root(t, found); };
  h.state = run.saved_numbers();
  if (distributed) h.global_ids = [&run] { return run.global_ids(); };  // checkpoints of the whole run
  if (run.changes_particles()) {
    h.after_step = [&run](Real t, const Real* y, const TimeLoopHooks::CarriedData& carried) {
      return run.after_step(t, y, carried);
    };
    h.restart_layout = [&run](const Checkpoint& c) { return run.restart_layout(c); };
    h.remove_active = [&run](Real t, const Real* y, const std::vector<std::size_t>& active) {
      return run.remove_active(t, y, active);
    };
    h.restore_particles = [&run](const StateLayout& layout) { run.restore_particles(layout); };
    h.wake_next = [&run](Real t, const Real* y, const std::vector<std::size_t>& active) {
      return run.wake_next(t, y, active);
    };
  }
  return h;
}

// Runs at a time (--concurrent-runs, 1 for a restart, a profile or a distributed run) and the
// OpenMP threads of each.
std::pair<int, int> lanes_and_threads(const Scene& scene, const ParsedRun& p) {
  int lanes = std::min<int>(std::max(1, p.control.concurrent_runs), static_cast<int>(p.runs.size()));
  if (p.core.profile || scene.world().distributed()) lanes = 1;  // one process-wide profile; ranks in step
  lanes = std::max(1, std::min(lanes, std::max(1, p.core.threads)));
  return {lanes, std::max(1, p.core.threads / lanes)};
}

// One run through the time loop: its exit status (report_time_loop_end) and, if not ok, why; the
// run and its result are kept for Scene::finished (called in the order of the runs).
struct RunOutcome {
  bool ended = false;
  int status = 0;
  std::string why;
  std::unique_ptr<SceneRun> run;
  TimeLoopResult result;
};

RunOutcome run_one(Scene& scene, const std::string& name, const ParsedRun& p, const Checkpoint* restart,
                   SetupWatchdog& watchdog) {
  const std::filesystem::path dir = p.core.out / scene.subdirectory(name);
  prepare_output_dir(dir, scene.program());
  SetupArming arming(watchdog);  // until the time loop's stepper exists
  RunOutcome out;
  out.run = scene.make_run(name, p.core);
  SceneRun& run = *out.run;
  if (restart && scene.world().distributed()) run.take_share(*restart);  // collective: this rank's particles
  const TimeLoopHooks hooks = hooks_of(run, arming, scene.world().distributed());
  TimeLoopSettings ts = default_settings(scene, name, p, dir, restart, run);
  run.settings(ts);
  if (lanes_and_threads(scene, p).first > 1) ts.progress_label = name;  // runs side by side: whose line
  const bool speaker = scene.world().rank() == 0;  // distributed: rank 0 prints
  ts.quiet = ts.quiet || !speaker;
  const StepperOptions so = run.stepper(p.core, scene.program());
  // A restart takes its state from the checkpoint: the initial conditions are not built.
  std::vector<Real> y0 = restart ? std::vector<Real>(run.layout().size(), 0.0) : run.initial_state();
  const detail::PlannedCost& cost = p.costs.at(name);
  // every rank alike: the line asks the system (collective); a distributed restart's state is the checkpoint's share
  if (cost.known && (!restart || (!scene.world().distributed() && restart->y.size() == y0.size()))) {
    const std::string line = detail::first_line(scene.program(), name, cost, run, so, restart ? restart->t : 0,
                                                restart ? restart->y.data() : y0.data(), p.core.t_end, ts.sample_every);
    if (speaker) std::fprintf(stderr, "%s\n", line.c_str());
  }
  if (speaker)
    std::fprintf(stderr, "%s: %s run, %zu particles%s, %s -> %s\n", scene.program().c_str(), name.c_str(),
                 run.layout().particles(), scene.world().distributed() ? " on rank 0" : "", describe(so).c_str(),
                 dir.c_str());
  out.result = run_time_loop(run.system(), run.layout(), so, std::move(y0), ts, hooks);
  std::printf("%s %s: %s\n", scene.program().c_str(), name.c_str(), format_stats(out.result.stats).c_str());
  if (out.result.status == TimeLoopStatus::Failed) out.why = out.result.failure;  // as report_time_loop_end prints it
  out.status = report_time_loop_end(out.result, speaker);
  out.ended = true;
  return out;
}

// The pictures of the runs that ended well (Scene::run_pictures), drawn by lanes that have no run
// left to start while the others still run; the scene's report draws those still pending.
class EarlyPictures {
 public:
  EarlyPictures(Scene& scene, const ParsedRun& p, int lanes)
      : scene_(scene), core_(p.core), runs_(p.runs.size()), on_(lanes > 1 && p.core.render && !scene.world().distributed()) {}
  void started() { ++started_; }
  void ended_well(const std::string& run) {  // under the driver's lock, after Scene::finished
    if (on_) queue_.push_back(run);
  }
  void ended() { ++ended_; }
  // In a lane whose run just ended well: while no run is left to start and another still runs,
  // draw the queue (the runs queued so far in one Python process: it starts once for them). Once
  // every run has ended, report() draws the rest with its comparisons, on every core.
  void draw_while_idle(std::mutex& lock) {
    while (on_ && started_.load() == runs_ && ended_.load() < runs_ && stop_requested() == 0) {
      std::vector<std::string> runs;
      {
        std::lock_guard<std::mutex> guard(lock);
        runs.swap(queue_);
      }
      if (runs.empty()) return;
      std::vector<PythonJob> jobs;
      for (const std::string& run : runs)
        for (PythonJob& job : scene_.run_pictures(run, core_)) jobs.push_back(std::move(job));
      if (!jobs.empty()) run_python_batch(jobs, true, 600, 1);
      std::lock_guard<std::mutex> guard(lock);
      for (const std::string& run : runs) scene_.set_run_pictures_drawn(run);
    }
  }

 private:
  Scene& scene_;
  const CoreOptions& core_;
  const std::size_t runs_;
  const bool on_;
  std::atomic<std::size_t> started_{0}, ended_{0};
  std::vector<std::string> queue_;
};

// Every run of p.runs (side by side when lanes_and_threads says so); Scene::finished in run order.
// Returns the runs that ended, in order.
std::vector<RunOutcome> run_all(Scene& scene, const ParsedRun& p, const Checkpoint* restart, SetupWatchdog& watchdog) {
  std::vector<RunOutcome> outcomes(p.runs.size());
  std::mutex finishing;
  std::size_t finished = 0;  // the runs handed to Scene::finished
  const auto [lanes, threads] = lanes_and_threads(scene, p);
  if (lanes > 1)
    std::fprintf(stderr, "%s: %zu runs, %d at a time on %d thread%s each (--concurrent-runs)\n", scene.program().c_str(),
                 p.runs.size(), lanes, threads, threads > 1 ? "s" : "");
  EarlyPictures pictures(scene, p, lanes);
  run_concurrently(p.runs.size(), lanes, threads, [&](std::size_t i) {
    pictures.started();
    RunOutcome o = run_one(scene, p.runs[i], p, restart, watchdog);
    const bool go_on = o.status == 0;  // a stop signal (checkpoint written) or a failure (last good state written)
    {
      std::lock_guard<std::mutex> lock(finishing);
      pictures.ended();
      outcomes[i] = std::move(o);
      for (; finished < outcomes.size() && outcomes[finished].ended; ++finished) {
        RunOutcome& r = outcomes[finished];
        scene.finished(p.runs[finished], *r.run, r.result);
        if (r.status == 0) pictures.ended_well(p.runs[finished]);
        r.run.reset();
      }
    }
    if (go_on) pictures.draw_while_idle(finishing);
    return go_on;
  });
  return outcomes;
}

void write_paraview_states(const Scene& scene, const std::filesystem::path& out, const std::vector<std::string>& done) {
  for (const Scene::ParaViewStateFile& state : scene.paraview_states(done))
    write_paraview_state_or_warn(out / state.file, state.views);
}

// run.json, kept by rank 0 alone (the other ranks of a distributed run keep none).
class RootRecord {
 public:
  RootRecord(bool root, const std::function<RunRecord()>& make) {
    if (root) record_.emplace(make());
  }
  void set(const std::string& key, Json value) {
    if (record_) record_->set(key, std::move(value));
  }
  void write() {
    if (record_) record_->write();
  }
  int finish_with_exit_code(int code, const std::string& reason = "") {
    return record_ ? record_->finish_with_exit_code(code, reason) : code;
  }

 private:
  std::optional<RunRecord> record_;
};

// What a distributed run cannot do yet (exit 2 on every rank: every rank parses the same options).
void check_distributed(const Scene& scene) {
  if (!scene.world().distributed()) return;
  if (!scene.supports_distributed_runs())
    exit_usage_error(scene.program(), "", "this example does not run distributed (mpirun) yet");
}

}  // namespace

// An example whose main does not distribute, started by mpirun: every rank would run the whole
// thing into the same files. Refused (exit 2 on every rank).
int run_scene_main(Scene& scene, int argc, char** argv) {
  if (MpiSession::launched_by_mpirun())
    exit_usage_error(scene.program(), "", "this example does not run distributed (mpirun); run it without mpirun");
  return run_scene_main(scene, argc, argv, Communicator{});
}

int run_scene_main(Scene& scene, int argc, char** argv, const Communicator& world) {
  scene.set_world(world);
  if (world.rank() > 0 && !std::freopen("/dev/null", "w", stdout)) return 1;  // rank 0 prints the reports
  const std::string program = scene.program();
  const std::optional<Checkpoint> restart = load_restart_option(argc, argv, program);
  ParsedRun p(scene);
  parse(p, scene, argc, argv, restart ? &*restart : nullptr);
  check_distributed(scene);
  start_run(p.core, program);
  // run.json: options, version, start (distributed: rank 0's, written last)
  RootRecord record(world.rank() == 0, [&] { return start_run_record(p.parser, p.given_values, p.core.out, world.size()); });
  // A stop during a set-up without a poll: no state to checkpoint, the record says so.
  auto stopped_in_setup = [&](int sig) {
    std::fprintf(stderr, "%s: stopped by signal %d during the set-up (no state to checkpoint yet)\n", program.c_str(), sig);
    return record.finish_with_exit_code(128 + sig, "stopped by signal " + std::to_string(sig) + " during the set-up");
  };
  SetupWatchdog watchdog([&](int sig) { stopped_in_setup(sig); });
  if (restart) {
    record.set("restart", restart->text("run") + " from t = " + std::to_string(restart->t));
    record.write();
  }
  const int probe_stop = world.distributed()
                             ? static_cast<int>(world.allreduce(std::int64_t{stop_requested()}, ReduceOp::Max))
                             : stop_requested();
  if (probe_stop != 0) return stopped_in_setup(probe_stop);  // during the cost probes (parse): nothing run yet
  try {
    if (const std::optional<int> code = scene.run_instead(p.core)) return record.finish_with_exit_code(*code);
    int status = 0;
    std::vector<std::string> done;
    std::string why;
    const std::vector<RunOutcome> outcomes = run_all(scene, p, restart ? &*restart : nullptr, watchdog);
    for (std::size_t i = 0; i < outcomes.size(); ++i) {
      if (!outcomes[i].ended) continue;
      done.push_back(p.runs[i]);
      if (status == 0) status = outcomes[i].status, why = outcomes[i].why;  // the first run that did not end ok
    }
    if (world.rank() == 0) write_paraview_states(scene, p.core.out, done);  // (serial or parallel frames)
    const int report = scene.report(p.core, p.runs, status == 0);
    if (const int sig = stop_requested(); sig != 0 && status == 0) {  // after a run ended: its outputs are whole
      std::fprintf(stderr, "%s: stopped by signal %d after %zu of %zu runs ended\n", program.c_str(), sig, done.size(),
                   p.runs.size());
      return record.finish_with_exit_code(128 + sig, "stopped by signal " + std::to_string(sig) + " after the run ended");
    }
    return record.finish_with_exit_code(status != 0 ? status : report, why);
  } catch (const StopRequested& stop) {  // a set-up loop's poll
    std::fprintf(stderr, "%s: stopped by signal %d during the set-up (no state to checkpoint yet)\n", program.c_str(),
                 stop.signal);
    return record.finish_with_exit_code(128 + stop.signal, "stopped by signal " + std::to_string(stop.signal) +
                                                               " during the set-up");
  } catch (const std::invalid_argument& e) {
    record.finish_with_exit_code(2, e.what());
    exit_usage_error(program, "", e.what());
  } catch (const std::exception& e) {
    // Distributed: an exception of one rank alone cannot be answered here (the others may wait in
    // a collective): MpiSession::run aborts every rank. A CollectiveError is every rank's.
    if (world.size() > 1 && !dynamic_cast<const CollectiveError*>(&e)) throw;
    std::fprintf(stderr, "%s: %s\n", program.c_str(), e.what());
    return record.finish_with_exit_code(1, e.what());
  }
}

}  // namespace sphark
