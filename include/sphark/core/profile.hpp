#pragma once
// Wall-time profile of a run, switched on by an example's --profile option.
//
// One process-wide accumulator (run_profile()) with a fixed set of phases. Code times a phase
// with a ScopedPhase object; when profiling is off a ScopedPhase costs one branch. Timers are
// started only outside OpenMP parallel regions (time a whole parallel loop, not a pair), so the
// accumulator needs no locking. Nested phases are allowed: Rhs encloses Neighbours, DensityH and
// Forces; Advance encloses Rhs. The summary derives
//   stepper (ARKODE vector work + step control) = Advance - Rhs
//   other RHS work                               = Rhs - Neighbours - DensityH - Forces.
#include <array>
#include <chrono>
#include <cstddef>
#include <iosfwd>

namespace sphark {

enum class Phase : std::size_t {
  Neighbours,  // neighbour list build / skin check
  DensityH,    // density summation and the h solve (SPMHD), density-type sums
  Forces,      // pair loops producing the time derivatives
  Rhs,         // one whole RHS evaluation (encloses the three above)
  Advance,     // inside Stepper::advance (encloses Rhs)
  Output,      // VTK, CSV, checkpoints, diagnostics
  Halo,        // distributed runs: halo plans, exchanges and agreements (with the waiting for other ranks)
  Count
};

const char* phase_name(Phase p);

// Work counted beside the time (printed under the table when some is non-zero).
enum class Tally : std::size_t {
  ListBuilds,     // neighbour list builds (every particle's row)
  DensitySolves,  // particles whose density / h was solved
  Count
};

class RunProfile {
 public:
  using Clock = std::chrono::steady_clock;
  bool enabled() const { return enabled_; }
  void enable(bool on = true) { enabled_ = on; }
  void reset() { seconds_.fill(0); calls_.fill(0); tallies_.fill(0); }
  void add(Phase p, double seconds) {
    seconds_[static_cast<std::size_t>(p)] += seconds;
    ++calls_[static_cast<std::size_t>(p)];
  }
  void tally(Tally k, long n) {
    if (enabled_) tallies_[static_cast<std::size_t>(k)] += n;
  }
  long tallied(Tally k) const { return tallies_[static_cast<std::size_t>(k)]; }
  double seconds(Phase p) const { return seconds_[static_cast<std::size_t>(p)]; }
  long calls(Phase p) const { return calls_[static_cast<std::size_t>(p)]; }
  // The table "phase  seconds  % of wall  calls" for a run that took `wall_seconds`.
  void print(std::ostream& os, double wall_seconds) const;

 private:
  bool enabled_ = false;
  std::array<double, static_cast<std::size_t>(Phase::Count)> seconds_{};
  std::array<long, static_cast<std::size_t>(Phase::Count)> calls_{};
  std::array<long, static_cast<std::size_t>(Tally::Count)> tallies_{};
};

// The process-wide profile.
RunProfile& run_profile();

// Adds the wall time between construction and destruction to `phase` (if profiling is on).
class ScopedPhase {
 public:
  explicit ScopedPhase(Phase phase) : phase_(phase), on_(run_profile().enabled()) {
    if (on_) start_ = RunProfile::Clock::now();
  }
  ~ScopedPhase() {
    if (on_)
      run_profile().add(phase_,
                        std::chrono::duration<double>(RunProfile::Clock::now() - start_).count());
  }
  ScopedPhase(const ScopedPhase&) = delete;
  ScopedPhase& operator=(const ScopedPhase&) = delete;

 private:
  Phase phase_;
  bool on_;
  RunProfile::Clock::time_point start_{};
};

}  // namespace sphark
