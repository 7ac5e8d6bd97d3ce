#pragma once
// The time loop's run (run/time_loop.hpp): the TimeLoop class, shared by time_loop.cpp (the
// loop, its records and ends) and time_loop_checkpoint.cpp (what a checkpoint holds, writing
// it, restoring from it). Private to src/run/.
#include <cmath>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sphark/integrate/stepper.hpp"
#include "sphark/io/pvtp_series.hpp"
#include "sphark/run/checkpoint.hpp"
#include "sphark/run/run_outputs.hpp"
#include "sphark/run/time_loop.hpp"

namespace sphark::detail {

// Counts of the stepper(s) before a restart, kept in the checkpoint under these names.
struct CountBase {
  Real steps = 0, attempts = 0, rhs_evals = 0, rhs_evals_implicit = 0, error_test_failures = 0,
       nonlinear_failures = 0, rhs_recoveries = 0, linear_solves = 0, particle_evals = 0;
  std::vector<std::pair<const char*, Real*>> bind();
  StepperStats total(StepperStats st) const;
  void set(const StepperStats& st);
};

// The first index k of the grid k x every after t (a checkpoint time t on the grid gives the next).
inline Real grid_index_after(Real t, Real every) { return std::floor(t / every * (1 + 1e-12)) + 1; }

// One run of the loop: its outputs (diagnostics CSV, VTK series, checkpoints), the state, the
// stepper, the grid position and the counts before a restart.
class TimeLoop {
 public:
  TimeLoop(OdeSystem& system, const StateLayout& initial_layout, StepperOptions opts, std::vector<Real> y0,
           const TimeLoopSettings& s, const TimeLoopHooks& hooks);
  TimeLoop(const TimeLoop&) = delete;  // binds_ points into this object
  TimeLoop& operator=(const TimeLoop&) = delete;

  // Integrates to t_end, a stop, a failure or an early end; the result without its wall time.
  TimeLoopResult run();

 private:
  void bind_checkpoint_scalars();
  void restore(const Checkpoint& c);
  bool stepper_data_applies(const Checkpoint& c) const;
  void restore_share(const Checkpoint& c);
  std::vector<Real> system_share(const Checkpoint& c, const std::vector<std::int64_t>& ids) const;
  void gather_whole_run(Checkpoint& c);
  void gather_system_data(Checkpoint& c, const std::vector<std::int64_t>& ids);
  void bound_steps(OdeSystem& system);
  StepperStats stats() const { return base_.total(stepper_->stats()); }
  void save(Real time);
  // Distributed runs (StepperOptions::communicator with MPI): every rank writes its piece of a
  // frame (parallel VTK), rank 0 the CSV and the checkpoints (with hooks_.global_ids: the whole
  // run's state, gather_whole_run); the stop poll is collective.
  bool distributed() const { return opts_.communicator.distributed(); }
  bool frames() const { return vtk_ || pvtk_; }
  void write_frame(Real time);
  void flush_csv() const {
    if (opts_.communicator.rank() == 0) csv_.flush();
  }
  int stop_signal() const;
  void record(Real time);
  void stop(int signal);
  void fail();
  void fail_in_hook(const std::exception& e);
  void end_at_root();
  void checkpoint_if_due();
  void finish();

  OdeSystem& system_;
  const TimeLoopSettings& s_;
  const TimeLoopHooks& hooks_;
  StepperOptions opts_;
  TimeLoopResult res_;
  const Real t_end_;
  const Real frame_every_;
  AtomicCsv csv_;
  std::optional<ResumableVtkSeries> vtk_;
  std::optional<ParallelVtkSeriesWriter> pvtk_;  // distributed runs
  Real sample_ = 0, next_frame_ = 0, next_checkpoint_;
  bool state_since_frame_ = false;  // a row was recorded after the last frame (finish() writes one)
  CountBase base_;
  std::vector<std::pair<std::string, Real*>> binds_;  // the checkpoint's scalars
  std::vector<Real> y_;
  std::vector<Real> system_resume_;  // a distributed restart: this rank's share of the system's resume data
  StateLayout layout_;  // changes when after_step resizes the state
  std::optional<StateLayout> removed_layout_;  // the layout after a removal inside the current step
  Real t_ = 0;
  std::unique_ptr<Stepper> stepper_;
};

}  // namespace sphark::detail
