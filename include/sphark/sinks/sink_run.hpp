#pragma once
// What a run of an SPMHD scene with sink particles (SpmhdOptions::sink_particles) needs from the
// run driver's SceneRun (run/scene.hpp), in one place for every scene that has sinks (the cloud
// collapse, the gravitating sphere):
//   after_step       the sink events between two steps (sinks/sink_events.hpp), the event log
//                    reloaded first from the numbers the checkpoint restores (saved_numbers)
//   remove_active    accretion and creation inside a step of particles on steps of their own,
//   restore_particles  its undoing, and the particles a creation needs woken (wake_next)
//   wake_next
//   saved_numbers    the log's counts as checkpointed run-loop numbers
//   restart_layout   the scheme takes the checkpoint's gas and sink counts (equal-mass gas)
//   columns/values   the diagnostics columns n_sinks and sink_mass (the mass of all sinks)
// and the sums that count the sinks: angular momentum about z (gas and sinks orbital + the sinks'
// spins), and the kernel-softened pair potential of the creation checks.
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sphark/run/checkpoint.hpp"
#include "sphark/run/time_loop.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "sphark/sinks/sink_events.hpp"

namespace sphark {

class SinkRunSupport {
 public:
  explicit SinkRunSupport(SinkParams params) : params_(std::move(params)) {}
  const SinkParams& params() const { return params_; }
  const SinkEventLog& log() const { return log_; }

  // SceneRun::after_step: sink_events at (t, y). created() says whether it (or the last
  // remove_active) created a sink.
  std::optional<TimeLoopHooks::Resize> after_step(SpmhdScheme<3>& scheme, Real t, const Real* y);
  bool created() const { return created_; }
  // SceneRun::remove_active: events_among_active at (t, y), counted in the log.
  std::optional<TimeLoopHooks::Resize> remove_active(SpmhdScheme<3>& scheme, Real t, const Real* y,
                                                     const std::vector<std::size_t>& active);
  // SceneRun::wake_next: creation_clump_to_wake at y.
  std::vector<std::size_t> wake_next(const SpmhdScheme<3>& scheme, const Real* y,
                                     const std::vector<std::size_t>& active) const {
    return creation_clump_to_wake(scheme, y, active, params_);
  }
  // SceneRun::restore_particles: the scheme takes the layout's species counts (as restart_layout;
  // the gas it gets back is no longer counted as accreted).
  void restore_particles(SpmhdScheme<3>& scheme, const StateLayout& layout);
  // SceneRun::saved_numbers: sink_creations, accreted_particles, first_sink_time.
  std::vector<std::pair<std::string, Real*>> saved_numbers();
  // SceneRun::restart_layout: the scheme takes the checkpoint's species counts (gas: the first
  // ones; the gas masses must be equal) and returns its layout.
  static StateLayout restart_layout(SpmhdScheme<3>& scheme, const Checkpoint& c);

  // The diagnostics columns {"n_sinks", "sink_mass"} and their values at y (sink_mass: the sum
  // over the sinks, 0 without one).
  static std::vector<std::string> columns();
  static std::array<Real, 2> values(const SpmhdScheme<3>& scheme, const Real* y);

 private:
  void reload_log();  // the log's counts from the checkpointed numbers
  void save_log();    // and back
  SinkParams params_;
  SinkEventLog log_;
  // the log's counts as checkpointed numbers (the log is reloaded from them before every event)
  Real creations_ = 0, accreted_ = 0, first_creation_t_ = -1;
  bool created_ = false;
};

// Angular momentum about z of the gas and the sinks (orbital, in particle order, gas first) plus
// the sinks' spins.
Real angular_momentum_z(const SpmhdScheme<3>& scheme, const Real* y);

// The gravity solver's kernel-softened (cubic spline) pair potential, symmetrised (Phantom's
// ptmass_create): SinkParams::pair_potential of a scheme with kernel-softened self-gravity.
PairPotential cubic_spline_pair_potential();

}  // namespace sphark
