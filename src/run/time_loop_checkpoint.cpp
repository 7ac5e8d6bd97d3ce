// The checkpoint half of the time loop (time_loop_impl.hpp): the scalars a checkpoint holds,
// writing one, restoring a run from one, and when one is due.
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>

#include "sphark/core/profile.hpp"
#include "sphark/io/vtk_series.hpp"
#include "sphark/parallel/global_state.hpp"
#include "sphark/run/checkpoint.hpp"
#include "time_loop_impl.hpp"

namespace sphark::detail {

std::vector<std::pair<const char*, Real*>> CountBase::bind() {
  return {{"steps", &steps}, {"attempts", &attempts}, {"rhs_evals", &rhs_evals},
          {"rhs_evals_implicit", &rhs_evals_implicit}, {"error_test_failures", &error_test_failures},
          {"nonlinear_failures", &nonlinear_failures}, {"rhs_recoveries", &rhs_recoveries},
          {"linear_solves", &linear_solves}, {"particle_evals", &particle_evals}};
}

StepperStats CountBase::total(StepperStats st) const {
  st.steps += static_cast<long>(steps);
  st.attempts += static_cast<long>(attempts);
  st.rhs_evals += static_cast<long>(rhs_evals);
  st.rhs_evals_implicit += static_cast<long>(rhs_evals_implicit);
  st.error_test_failures += static_cast<long>(error_test_failures);
  st.nonlinear_failures += static_cast<long>(nonlinear_failures);
  st.rhs_recoveries += static_cast<long>(rhs_recoveries);
  st.linear_solves += static_cast<long>(linear_solves);
  st.particle_evals += static_cast<long>(particle_evals);
  return st;
}

void CountBase::set(const StepperStats& st) {
  steps = st.steps, attempts = st.attempts, rhs_evals = st.rhs_evals, rhs_evals_implicit = st.rhs_evals_implicit;
  error_test_failures = st.error_test_failures, nonlinear_failures = st.nonlinear_failures;
  rhs_recoveries = st.rhs_recoveries, linear_solves = st.linear_solves, particle_evals = st.particle_evals;
}

void TimeLoop::bind_checkpoint_scalars() {
  binds_ = {{"sample", &sample_}, {"next_frame", &next_frame_}, {"next_checkpoint", &next_checkpoint_}};
  for (auto& [name, ptr] : base_.bind()) binds_.emplace_back(name, ptr);
  binds_.insert(binds_.end(), hooks_.state.begin(), hooks_.state.end());
}

// Whether the checkpoint's stepper data (Stepper::resume_data) belongs to this run's stepper:
// the data of another method (a restart that changes --stepper) is dropped, and the new stepper
// starts afresh at the checkpoint's state (its first step evaluates f, bins, partitions), said in
// one line. Checkpoints of before 2026-12-07 name no stepper: their data is handed over as it is.
bool TimeLoop::stepper_data_applies(const Checkpoint& c) const {
  if (c.stepper_data.empty() || !c.has_text("stepper") || c.text("stepper") == opts_.method) return true;
  if (opts_.communicator.rank() == 0)
    std::fprintf(stderr, "%s: --restart: the checkpoint's stepper data is %s's; %s starts afresh at t = %.9g\n",
                 s_.program.c_str(), c.text("stepper").c_str(), opts_.method.c_str(), c.t);
  return false;
}

void TimeLoop::restore(const Checkpoint& c) {
  if (distributed()) {
    restore_share(c);
  } else {
    if (hooks_.restart_layout) layout_ = hooks_.restart_layout(c);
    if (auto why = layout_mismatch(c, layout_)) throw std::runtime_error("--restart: " + *why);
    y_ = c.y;
    opts_.resume_data = stepper_data_applies(c) ? c.stepper_data : std::vector<Real>{};
  }
  t_ = c.t;
  for (auto& [name, ptr] : binds_) {
    // particle_evals (issue #17) is newer than the other counts: a checkpoint without it counts
    // from the restart on.
    const bool optional = name == "particle_evals";
    *ptr = !optional || c.has_scalar(name) ? c.scalar(name) : 0;
  }
  if (distributed() && opts_.communicator.rank() != 0) base_.particle_evals = 0;  // (the checkpoint's is the sum)
  // Another sampling, frame or checkpoint interval than the checkpointed run's: continue on the
  // new grid from the checkpoint time on.
  if (c.scalar("sample_every") != s_.sample_every || !(sample_ * s_.sample_every > t_))  // (the latter: a corrupt index)
    sample_ = grid_index_after(t_, s_.sample_every);
  if (c.scalar("frame_every") != frame_every_) next_frame_ = grid_index_after(t_, frame_every_) * frame_every_;
  if (c.scalar("checkpoint_every") != s_.checkpoint_every && s_.checkpoint_every > 0)
    next_checkpoint_ = grid_index_after(t_, s_.checkpoint_every) * s_.checkpoint_every;
  csv_.restore(c.text("diagnostics.csv"));
  // frames_dir: absent in checkpoints of before 2026-12-02
  const std::filesystem::path earlier = c.has_text("frames_dir") ? std::filesystem::path(c.text("frames_dir")) : "";
  if (vtk_) vtk_->restore(c.text("frames"), earlier);
  if (pvtk_) pvtk_->restore(parse_frame_list(c.text("frames"), s_.frames_dir, earlier));
  opts_.initial_dt = c.last_dt;
}

namespace {
// Stepper resume data of one value per state entry followed by a tail of one or two values the
// same on every rank (the leapfrog's: its derivative, then a time and its planned stable step)
// apart: the per-entry part, and the tail. Throws unless it is so.
std::pair<std::vector<Real>, std::vector<Real>> per_entry_and_tail(const std::vector<Real>& data, std::size_t entries,
                                                                   const char* where) {
  if (data.size() != entries + 1 && data.size() != entries + 2)
    throw std::runtime_error(std::string(where) + ": the stepper's resume data is not one value per state entry + 1 or 2");
  const auto split = data.begin() + static_cast<std::ptrdiff_t>(entries);
  return {std::vector<Real>(data.begin(), split), std::vector<Real>(split, data.end())};
}
}  // namespace

// A distributed restart (checkpoint of any number of ranks, or of a serial run): the state and
// the stepper's per-entry data of this rank's particles (hooks_.global_ids: the share the system
// took before the loop, SceneRun::take_share).
void TimeLoop::restore_share(const Checkpoint& c) {
  if (!hooks_.global_ids) throw std::logic_error("a distributed restart without a global_ids hook");
  const StateLayout whole = layout_.with_count(layout_.primary(), c.particles());
  if (auto why = layout_mismatch(c, whole)) throw std::runtime_error("--restart: " + *why);
  const std::vector<std::int64_t> ids = hooks_.global_ids();
  if (ids.size() != layout_.particles()) throw std::logic_error("a distributed restart: the ids do not fit the layout");
  y_ = share_of(whole, c.y, ids);
  system_resume_ = system_share(c, ids);
  opts_.resume_data.clear();
  if (c.stepper_data.empty() || !stepper_data_applies(c)) return;
  const auto [per_entry, tail] = per_entry_and_tail(c.stepper_data, c.y.size(), "--restart");
  opts_.resume_data = share_of(whole, per_entry, ids);
  opts_.resume_data.insert(opts_.resume_data.end(), tail.begin(), tail.end());
}

// The system's resume data (OdeSystem::resume_shape: per-particle blocks, then a tail) of the
// particles `ids` out of the checkpoint's, every particle's by global id.
std::vector<Real> TimeLoop::system_share(const Checkpoint& c, const std::vector<std::int64_t>& ids) const {
  if (c.system_data.empty()) return {};
  if (!c.has_scalar("system_per_particle"))
    throw std::runtime_error("--restart: the checkpoint's system data has no shape (written before 2026-12-05): "
                             "restart it serially");
  const auto per = static_cast<std::size_t>(c.scalar("system_per_particle"));
  const auto tail = static_cast<std::size_t>(c.scalar("system_tail"));
  const std::size_t n = c.particles(), m = ids.size();
  if (c.system_data.size() != per * n + tail) throw std::runtime_error("--restart: the system data does not fit its shape");
  std::vector<Real> out(per * m + tail);
  for (std::size_t k = 0; k < per; ++k)
    for (std::size_t i = 0; i < m; ++i) out[k * m + i] = c.system_data[k * n + static_cast<std::size_t>(ids[i])];
  std::copy(c.system_data.end() - static_cast<std::ptrdiff_t>(tail), c.system_data.end(), out.end() - static_cast<std::ptrdiff_t>(tail));
  return out;
}

// The system's resume data of a distributed run on rank 0: its per-particle blocks by global id
// (OdeSystem::resume_shape), then rank 0's tail (every rank's is the same).
void TimeLoop::gather_system_data(Checkpoint& c, const std::vector<std::int64_t>& ids) {
  const Communicator& comm = opts_.communicator;
  const OdeSystem::ResumeShape shape = system_.resume_shape();
  const auto per = static_cast<std::size_t>(shape.per_particle), tail = static_cast<std::size_t>(shape.tail);
  comm.check(c.system_data.size() == per * ids.size() + tail,
             "checkpoints of distributed runs: the system's resume data is not in per-particle blocks");
  if (per == 0 && tail == 0) return;
  const std::vector<Real> tail_values(c.system_data.end() - static_cast<std::ptrdiff_t>(tail), c.system_data.end());
  c.system_data.resize(per * ids.size());
  if (per > 0) c.system_data = gather_particles(comm, ids, c.system_data, std::vector<int>(per, 1));
  if (comm.rank() == 0) c.system_data.insert(c.system_data.end(), tail_values.begin(), tail_values.end());
}

// A distributed run's checkpoint: the whole run as a serial run of the same particles writes it,
// assembled on rank 0 (c already holds this rank's values; the other ranks' c is then empty).
void TimeLoop::gather_whole_run(Checkpoint& c) {
  const Communicator& comm = opts_.communicator;
  comm.check(layout_.species().size() == 1, "checkpoints of distributed runs hold one species");
  comm.check(c.stepper_data.empty() || c.stepper_data.size() == y_.size() + 1 || c.stepper_data.size() == y_.size() + 2,
             "checkpoints of distributed runs: this stepper's resume data is not per state entry");
  const std::vector<std::int64_t> ids = hooks_.global_ids();
  const std::vector<int> components = field_components(layout_);
  const auto global = static_cast<std::size_t>(comm.allreduce(static_cast<std::int64_t>(ids.size()), ReduceOp::Sum));
  c.species = describe_layout(layout_.with_count(layout_.primary(), global));
  c.y = gather_particles(comm, ids, y_, components);
  gather_system_data(c, ids);
  if (c.stepper_data.empty()) return;
  const auto [per_entry, tail] = per_entry_and_tail(c.stepper_data, y_.size(), "checkpoint");
  c.stepper_data = gather_particles(comm, ids, per_entry, components);
  if (comm.rank() == 0) c.stepper_data.insert(c.stepper_data.end(), tail.begin(), tail.end());
}

void TimeLoop::save(Real time) {
  if (distributed() && !hooks_.global_ids) {  // a distributed run without checkpoints
    flush_csv();
    return;
  }
  ScopedPhase phase(Phase::Output);
  Checkpoint c;
  c.program = s_.program;
  c.argv = s_.argv;
  c.species = describe_layout(layout_);
  c.t = time;
  c.last_dt = stepper_->stats().last_dt > 0 ? stepper_->stats().last_dt : opts_.initial_dt;
  CountBase now;  // the counts so far: the restart's base
  now.set(stats());
  if (distributed())  // the whole run's work (a restart counts it on rank 0, restore())
    now.particle_evals = static_cast<Real>(opts_.communicator.allreduce(std::int64_t(stats().particle_evals), ReduceOp::Sum));
  for (auto& [name, ptr] : binds_) {
    bool counted = false;
    for (auto& [cname, cptr] : now.bind())
      if (name == cname) c.set_scalar(name, *cptr), counted = true;
    if (!counted) c.set_scalar(name, *ptr);
  }
  c.set_scalar("sample_every", s_.sample_every);
  c.set_scalar("frame_every", frame_every_);
  c.set_scalar("checkpoint_every", s_.checkpoint_every);
  c.set_text("run", s_.run);
  for (const auto& [k, v] : s_.texts) c.set_text(k, v);
  c.set_text("diagnostics.csv", csv_.text());
  if (frames()) {
    c.set_text("frames", vtk_ ? vtk_->text() : frame_list_text(pvtk_->frames()));
    c.set_text("frames_dir", std::filesystem::absolute(s_.frames_dir).string());
  }
  c.y = y_;
  c.stepper_data = stepper_->resume_data();
  c.set_text("stepper", opts_.method);  // whose data that is (stepper_data_applies)
  c.system_data = system_.resume_data();
  const OdeSystem::ResumeShape shape = system_.resume_shape();  // a distributed restart takes its share by it
  c.set_scalar("system_per_particle", shape.per_particle);
  c.set_scalar("system_tail", shape.tail);
  if (distributed()) gather_whole_run(c);
  flush_csv();
  res_.checkpoint = s_.checkpoint;
  opts_.communicator.collectively([&] {
    if (opts_.communicator.rank() == 0) save_checkpoint(s_.checkpoint, c);
  });
}

// A checkpoint at the first sample at or after every multiple of checkpoint_every.
void TimeLoop::checkpoint_if_due() {
  if (!(s_.checkpoint_every > 0 && t_ >= next_checkpoint_ - 1e-12 * t_end_)) return;
  if ((t_ - next_checkpoint_) / s_.checkpoint_every < 1e3) {
    while (next_checkpoint_ <= t_ + 1e-12 * t_end_) next_checkpoint_ += s_.checkpoint_every;
  } else {  // an interval far below the sampling: one jump, not a loop per interval passed
    next_checkpoint_ = grid_index_after(t_, s_.checkpoint_every) * s_.checkpoint_every;
  }
  save(t_);
}

}  // namespace sphark::detail
