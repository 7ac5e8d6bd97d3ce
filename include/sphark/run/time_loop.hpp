#pragma once
// The run driver shared by every time-integrating example: integrate an OdeSystem from an initial
// state (or a checkpoint) to t_end, sampling diagnostics on a fixed time grid, writing VTK frames,
// checkpoints and the diagnostics CSV atomically, polling SIGINT/SIGTERM (between output times and,
// through StepperOptions::interrupt, before every RHS evaluation: a stop ends the run within one
// evaluation, with a checkpoint of the last accepted step), reporting progress and
// (with --profile) the wall-time split; on a blow-up it writes the last good state (VTK frame +
// checkpoint) and says why, when and for which particles.
//
//   TimeLoopSettings s;  s.program = "my_scene"; s.run = "main"; s.t_end = ...; s.sample_every = ...;
//   s.diagnostics_csv = dir / "diagnostics.csv";  s.columns = {"t", "energy", ...};
//   s.frames_dir = dir;  s.frames_basename = "my_scene";  s.frame_every = ...;
//   s.checkpoint = dir / "checkpoint.bin";  s.checkpoint_every = ...;  s.restart = ckpt_or_null;
//   TimeLoopHooks h;
//   h.diagnostics = [&](Real t, const Real* y, const StepperStats&) { return std::vector<Real>{t, ...}; };
//   h.frame = [&](Real t, const Real* y) { ...; return ParticleFrame{...}; };   // arrays live in buffers you own
//   const TimeLoopResult r = run_time_loop(system, layout, stepper_options, y0, s, h);
//   return report_time_loop_end(r);  // prints the outcome; 0 ok, 3 failed, 128 + signal when stopped
//
// The diagnostics row is taken at t = 0 (not on a restart) and after every advance() to the next
// grid time k * sample_every (t_end is snapped onto the grid when it is a multiple of it, so runs
// to t1 < t2 pass bit-identical times); frames are written at t = 0, every frame_every and at the
// end. Everything a restart needs (the state, the stepper's resume data, the step size, the
// counts, the grid position, the CSV rows, the frame list, the caller's `state` scalars and
// `texts`) goes into the checkpoint; a restart continues bit for bit with the leapfrog and any
// fixed-step method whenever the system's rhs depends on y alone.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sphark/integrate/ode_system.hpp"
#include "sphark/integrate/stepper_options.hpp"
#include "sphark/io/particle_frame.hpp"
#include "sphark/run/checkpoint.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark {

// The step floor: a step shorter than kStepFloorFraction x t_end is an error, before the run for
// a fixed --dt (exit 2, check_step_option in run/restart.hpp) and during it for any stepper
// (StepperOptions::step_floor: the run fails, exit 3, with the last good state). At the floor a
// run needs 1e9 steps; the finest runs of the examples take steps of ~1e-4 t_end.
inline constexpr Real kStepFloorFraction = 1e-9;

struct TimeLoopSettings {
  std::string program;                  // "water_drop": checkpoint owner and message prefix
  std::string run = "run";              // which run / variant (checkpoint text "run")
  std::vector<std::string> argv;        // this run's options, stored in the checkpoint
  std::vector<std::pair<std::string, std::string>> texts;  // extra checkpoint texts (e.g. "scene")
  Real t_end = 1;
  Real sample_every = 0;                // diagnostics grid (> 0 required)
  std::filesystem::path diagnostics_csv;  // written atomically at every frame, checkpoint and end
  std::vector<std::string> columns;     // its header
  std::filesystem::path frames_dir;     // "" : no VTK frames
  std::string frames_basename;          // <frames_dir>/<basename>_NNNNN.vtp + <basename>.pvd
  Real frame_every = 0;                 // 0: first and last only; the final state is always a frame
  std::filesystem::path checkpoint;     // written on failure / signal, and every checkpoint_every
  Real checkpoint_every = 0;            // > 0: also at the end
  const Checkpoint* restart = nullptr;  // continue from this checkpoint (checked by the caller)
  Real inject_nan_at = 0;               // > 0: testing aid, the RHS turns non-finite from then on
  // Steps below min_dt_fraction x min(initial stable step, sample_every) end the run as a failure
  // (unless StepperOptions::min_dt is set).
  Real min_dt_fraction = 1e-6;
  // Every step must be at least step_floor_fraction x t_end (unless StepperOptions::step_floor
  // is set): see kStepFloorFraction.
  Real step_floor_fraction = kStepFloorFraction;
  bool quiet = false;                   // no progress lines
  double progress_interval = 2;         // seconds between progress lines
  std::string progress_label;           // prefix of the progress lines (runs side by side: the run)
};

struct TimeLoopHooks {
  // The diagnostics row at (t, y) (columns as TimeLoopSettings::columns); `total` counts every
  // step and rhs evaluation since t = 0 (across restarts). Called at every grid time, and at the
  // last good state of a failed run (before its frame). Required.
  std::function<std::vector<Real>(Real t, const Real* y, const StepperStats& total)> diagnostics;
  // The VTK frame of (t, y), called right after diagnostics() at the same (t, y); its arrays must
  // stay valid until the next call. Required if frames_dir is set.
  std::function<ParticleFrame(Real t, const Real* y)> frame;
  // Optional: true ends the run early but normally after the sample at t (e.g. a blow-up the scene
  // measures, like the non-conservative cleaning's growth).
  std::function<bool(Real t)> finished;
  // Optional: called when the stepper stops at a root of the system's roots() (which ones: the
  // stepper's roots_found()); true ends the run early after a sample and a frame at that t, false (or no
  // hook) continues the integration.
  std::function<bool(Real t, const std::vector<int>& found)> root;
  // Named run-loop numbers saved in checkpoints and restored on restart (bound by pointer).
  std::vector<std::pair<std::string, Real*>> state;
  // Optional: called after every step (the loop then steps one by one, Stepper::step) with the
  // state at t and a getter of the stepper's carried data there (Stepper::carried_data: the
  // leapfrog's derivative; empty for ARKODE); a system whose particle count changes (sinks
  // created, gas accreted, particles migrating to other ranks) returns its new layout and state,
  // which the stepper then continues from (Stepper::resize).
  struct Resize {
    StateLayout layout;
    std::vector<Real> y;
    std::vector<Real> atol;  // per entry of the new state when the run uses per-entry tolerances
    // Where the new entries came from (a reordering, or a removal such as accretion): new entry k
    // continues old entry entry_source[k]; the stepper's carried data (Stepper::carried_data)
    // then moves with the entries, unless an entry has none (kNoEntrySource: a new sink's). Empty,
    // or an entry without a source: the stepper starts afresh at y (Stepper::resize), unless
    // `carried` is given.
    std::vector<std::size_t> entry_source;
    // The carried data of the new state, one value per entry (e.g. migrated with it; a rank left
    // without particles passes an empty one: every rank of a distributed run the same choice).
    std::optional<std::vector<Real>> carried;
  };
  using CarriedData = std::function<std::vector<Real>()>;
  std::function<std::optional<Resize>(Real t, const Real* y, const CarriedData& carried)> after_step;
  // Optional, with after_step: at an event inside the top step of a stepper whose particles
  // take steps of their own, removes some of the particles active there (gas accreted onto a
  // sink; StepperOptions::remove_active): the new layout and state, with entry_source (new entry
  // k continues old entry entry_source[k]; every new entry has one). restore_particles gives the
  // system back the particles of `layout` (a step that fails or is interrupted after a removal
  // rolls back to its start).
  std::function<std::optional<Resize>(Real t, const Real* y, const std::vector<std::size_t>& active)> remove_active;
  std::function<void(const StateLayout& layout)> restore_particles;
  // Optional, with after_step: after remove_active, the particles that must end their steps at the
  // stepper's next event (StepperOptions::wake_next), e.g. a sink candidate's neighbourhood.
  std::function<std::vector<std::size_t>(Real t, const Real* y, const std::vector<std::size_t>& active)> wake_next;
  // Optional, with after_step: on a restart, the system takes the checkpoint's species counts
  // and returns its layout (which must then match the checkpoint's).
  std::function<StateLayout(const Checkpoint& c)> restart_layout;
  // Distributed runs (StepperOptions::communicator with MPI), required for their checkpoints:
  // the global ids of this rank's particles in state order (0 .. N-1 over the ranks; one
  // species). A checkpoint then holds the whole run as a serial run of the same particles writes
  // it (rank 0 writes it; the stepper's per-entry resume data travels with the state), and a
  // restart from one (of any number of ranks, or serial) takes the values of these ids: the
  // caller has given the system its share of the checkpoint's particles (SceneRun::take_share).
  std::function<std::vector<std::int64_t>()> global_ids;
  // Optional: called once the stepper exists, before the first output (the set-up is over: from
  // here on a stop signal is answered with a checkpoint).
  std::function<void()> started;
};

enum class TimeLoopStatus { Reached, EndedEarly, Failed, Stopped };

struct TimeLoopResult {
  std::string program, run;
  TimeLoopStatus status = TimeLoopStatus::Reached;
  std::string failure;               // why the stepper gave up (Failed)
  int signal = 0;                    // SIGINT / SIGTERM (Stopped)
  Real t_reached = 0;
  std::filesystem::path checkpoint;  // last checkpoint written ("" if none)
  std::filesystem::path last_frame;  // last VTK frame written ("" if none)
  std::string diagnostics;           // the CSV text (header + every row since t = 0)
  StepperStats stats;                // totals since t = 0
  double wall_seconds = 0;           // of this process's part of the run
  bool ok() const { return status == TimeLoopStatus::Reached || status == TimeLoopStatus::EndedEarly; }
};

// Runs the loop above. Throws std::runtime_error for a checkpoint that does not fit (layout,
// missing entries) and for output files that cannot be written.
TimeLoopResult run_time_loop(OdeSystem& system, const StateLayout& layout, StepperOptions options,
                             std::vector<Real> y0, const TimeLoopSettings& settings, const TimeLoopHooks& hooks);

// Prints the outcome of a failed or stopped run to stderr (reason, time, particles, where the
// last good state is, how to continue) and returns the exit code: 0 (ok), 3 (failed),
// 128 + signal (stopped).
int report_time_loop_end(const TimeLoopResult& r, bool print = true);  // print false: the code alone

// One column of a CSV text as numbers (std::runtime_error if the column is missing).
std::vector<Real> csv_column(const std::string& csv_text, const std::string& column);

}  // namespace sphark
