#pragma once
// Sink-particle events between two steps of an SPMHD run with sinks (SpmhdOptions::sink_particles):
// at the state (t, y) just reached, gas is accreted onto the sinks (sinks/sink_accretion.hpp) or,
// if none is, a sink is created at the densest gas particle when every check of
// sinks/sink_creation.hpp allows it. Either changes the particle set: the scheme takes the new set
// (SpmhdScheme::change_particles) and the function returns the new layout and state for the time
// loop (TimeLoopHooks::after_step, which resizes the stepper). Mass, linear and angular momentum
// (orbital + spin) carry over to round-off; every other particle's state bit for bit.
#include <map>
#include <optional>

#include "sphark/run/time_loop.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "sphark/sinks/sink_creation.hpp"

namespace sphark {

// What the events did so far (for the run's summary).
struct SinkEventLog {
  long creations = 0;
  long forced_creations = 0;           // of them, made past the checks (SinkParams::forced_creation_factor)
  long accreted_particles = 0;
  Real first_creation_time = -1;
  std::map<SinkCheck, long> refusals;  // candidate refused, by the first check that failed
  // An event would have taken every gas particle (an isolated cloud collapsing onto its sink):
  // it is not made (the scheme needs gas) and the run should end (SceneRun::finished).
  bool gas_exhausted = false;
};

// The sinks of state y (accretion radius params.accretion_radius each).
std::vector<Sink> sinks_of(const SpmhdScheme<3>& scheme, const Real* y, Real accretion_radius);

// A candidate for a new sink: a gas particle denser than rho_sink at the scheme's last
// evaluation (the creation checks may still refuse it).
bool sink_creation_due(const SpmhdScheme<3>& scheme, const SinkParams& params);

// The sink events inside a step of particles on steps of their own (TimeLoopHooks::remove_active;
// Phantom's check 3 for creation), among the `active` particles (particle indices,
// gas first, ascending), whose entries must all be at the time t of y (the other particles'
// positions too; their other entries may lie mid-step):
//   accretion  of the active gas the sinks accrete at y (the same test as sink_events');
//   creation   if none is accreted and a gas particle was denser than rho_sink at the scheme's
//              last evaluation (an evaluation at this event: its densities, h, div v and
//              potential; y's positions and velocities): the creation checks of sink_events,
//              made only when the candidate and every gas particle within r_acc of it are
//              active (Phantom's check 3; otherwise nothing happens and nothing is counted).
// The new layout and state with entry_source (kNoEntrySource for a new sink's entries);
// nothing when nothing happened or the event would take every gas particle (sink_events then
// decides).
std::optional<TimeLoopHooks::Resize> events_among_active(SpmhdScheme<3>& scheme, Real t, const Real* y,
                                                         const std::vector<std::size_t>& active,
                                                         const SinkParams& params, SinkEventLog& log);

// What events_among_active needs to make a sink at the next event: the gas particles within r_acc
// of the candidate (a gas particle denser than rho_sink at the last evaluation, not within the
// creation radius of a sink) that are not `active` now (TimeLoopHooks::wake_next); none when
// there is no such candidate.
std::vector<std::size_t> creation_clump_to_wake(const SpmhdScheme<3>& scheme, const Real* y,
                                                const std::vector<std::size_t>& active, const SinkParams& params);

// The events at a step's end (TimeLoopHooks::after_step): the new layout and state with
// entry_source, as events_among_active's, so that a leapfrog's next kick uses the derivatives
// of the kept entries (no evaluation after an accretion, as in the block steps and in Phantom);
// a new sink's entries have none (the stepper then evaluates afresh).
std::optional<TimeLoopHooks::Resize> sink_events(SpmhdScheme<3>& scheme, Real t, const Real* y, const SinkParams& params,
                                                 SinkEventLog& log);

}  // namespace sphark
