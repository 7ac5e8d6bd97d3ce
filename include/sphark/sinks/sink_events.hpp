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
  long accreted_particles = 0;
  Real first_creation_time = -1;
  std::map<SinkCheck, long> refusals;  // candidate refused, by the first check that failed
  // An event would have taken every gas particle (an isolated cloud collapsing onto its sink):
  // it is not made (the scheme needs gas) and the run should end (SceneRun::finished).
  bool gas_exhausted = false;
};

// The sinks of state y (accretion radius params.accretion_radius each).
std::vector<Sink> sinks_of(const SpmhdScheme<3>& scheme, const Real* y, Real accretion_radius);

// Whether sink_events at y would change the particles: gas it would accrete (the same test), or
// a candidate for a new sink — a gas particle denser than rho_sink at the scheme's last
// evaluation (of y; the creation checks that could still refuse it need a new evaluation).
bool sink_event_due(const SpmhdScheme<3>& scheme, const Real* y, const SinkParams& params);

std::optional<TimeLoopHooks::Resize> sink_events(SpmhdScheme<3>& scheme, Real t, const Real* y, const SinkParams& params,
                                                 SinkEventLog& log);

}  // namespace sphark
