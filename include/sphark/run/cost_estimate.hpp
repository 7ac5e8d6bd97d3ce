#pragma once
// The predicted cost of a run, before it starts (issue #21; docs/robustness.md, "Cost"):
//  - particles: from the options alone (Scene::predicted_particles), before anything is built;
//  - memory: a probe, the same run with about kProbeParticles particles, is built, takes a few
//    steps, and the heap it keeps is measured: every buffer of the scheme, its neighbour lists,
//    the state and the stepper's vectors. Bytes per particle x particles, plus the checkpoint's
//    copies of the state, against memory_available_bytes(): a run that does not fit is refused
//    (exit 2) before any of its own arrays exist;
//  - steps: t_end / dt0 with dt0 = fixed dt, or cfl_safety x max_stable_dt at the first state
//    (adaptive ARKODE runs: their step cap, so the count is a lower bound); time: steps x the
//    probe's wall time per step, scaled by particles / probe particles.
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/integrate/ode_system.hpp"
#include "sphark/integrate/stepper_options.hpp"

namespace sphark {

inline constexpr Real kProbeParticles = 4096;

// Memory this process may still allocate, in bytes: MemAvailable of /proc/meminfo, lowered to
// the cgroup's memory.max - memory.current where that is smaller, and to SPHARK_MEMORY_LIMIT when
// set (bytes, or with a K/M/G/T suffix: a user's own cap, and the tests' stand-in for a smaller
// machine). nullopt if none of them can be read.
std::optional<double> memory_available_bytes();
// "MemAvailable:   23456 kB" in a /proc/meminfo text, in bytes.
std::optional<double> parse_mem_available(const std::string& meminfo);
// "16G", "512M", "1.5K", "1000000" -> bytes; nullopt for anything else (negative, non-finite, junk).
std::optional<double> parse_byte_size(const std::string& text);
// Heap bytes in use now, all threads (glibc mallinfo2; an AddressSanitizer build: its allocator's).
double heap_bytes_in_use();

// What a probe run is: an owner that keeps the system alive, the system, its first state, the
// stepper options of the run, its particles, and optionally its diagnostics (called once, so
// that their buffers are counted).
struct ProbeSubject {
  std::shared_ptr<void> owner;
  OdeSystem* system = nullptr;
  std::vector<Real> y0;
  StepperOptions stepper;
  double particles = 0;
  std::function<void(Real t, const Real* y)> diagnostics;
};

struct ProbeMeasurement {
  double particles = 0;
  double heap_bytes = 0;   // kept by the subject and its stepper after the steps
  double state_bytes = 0;  // one state vector
  long steps = 0;
  double seconds_per_step = std::numeric_limits<double>::quiet_NaN();
};

// Builds the subject, integrates it for one step of warm-up and about three timed steps (never
// beyond t_end) and measures.
// Exceptions of `build` propagate; a probe that fails to step still measures its memory.
ProbeMeasurement measure_probe(const std::function<ProbeSubject()>& build, Real t_end);

struct CostEstimate {
  double particles = 0;
  double bytes_per_particle = 0;  // measured (probe) + checkpoint copies of the state
  double bytes = 0;
  double probe_particles = 0;
  std::optional<double> available;  // memory_available_bytes()
  double first_step = std::numeric_limits<double>::quiet_NaN();  // dt0
  double steps = std::numeric_limits<double>::quiet_NaN();
  bool steps_at_least = false;  // first_step bounds every step: adaptive ARKODE (the cap, or an uncapped run's stability reach), a scene whose stable step only falls (SceneRun::stable_step_falls)
  double seconds = std::numeric_limits<double>::quiet_NaN();
  bool fits() const { return !available || bytes <= *available; }
  bool longer_than_a_day() const { return seconds > 86400; }
};

// Memory of a run of `particles` particles from its probe.
CostEstimate estimate_memory(double particles, const ProbeMeasurement& probe);
// Adds steps and time of the run from (t0, y0) to t_end with stepper options `so` (see above).
// longest_step > 0: no step is longer (the time loop's diagnostics interval: it lands on every
// row), so the steps are at least (t_end - t0) / longest_step.
void estimate_time(CostEstimate& e, OdeSystem& system, const StepperOptions& so, Real t0, const Real* y0,
                   Real t_end, Real longest_step, const ProbeMeasurement& probe);

// "3.1 GB", "512 kB"; "2.5 s", "3.4 h", "12 days".
std::string bytes_text(double bytes);
std::string duration_text(double seconds);
// Why a run does not fit (the value of a one-line error): "3.1e7 particles need ~52 GB (1.7 kB
// each, measured on a 4096-particle probe); 21 GB available".
std::string memory_refusal(const CostEstimate& e);
// The first line of a run: "<program>: <run> run: predicted 1976 particles, 11 MB of 21 GB
// available, >= 720 steps, ~2.5 s"; a run predicted to take longer than a day starts with
// "<program>: <run> run will take LONGER THAN A DAY: ...".
std::string cost_line(const std::string& program, const std::string& run, const CostEstimate& e);

}  // namespace sphark
