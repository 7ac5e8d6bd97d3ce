#pragma once
// SIGINT / SIGTERM as a polite stop request: the handler only records the signal number (an
// atomic, lock-free: safe to read from any thread); no work (no I/O, no allocation) happens
// inside it. Who looks at the request (docs/robustness.md, "Signals"):
//  - every stepper, before every right-hand-side evaluation and every step
//    (StepperOptions::interrupt): the time loop then checkpoints the last accepted step;
//  - long set-up loops (relaxation, random placement): throw_if_stop_requested();
//  - the run driver's set-up watchdog (SetupWatchdog below) for set-up work that has no poll of
//    its own (neighbour builds, allocation of the particle set): it ends the process shortly
//    after the signal, with the run record finished, since no state exists yet to checkpoint.
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace sphark {

// Installs the handler for SIGINT and SIGTERM (idempotent).
void install_stop_handlers();
// 0 while no stop was requested, else the number of the first signal received.
int stop_requested();
// Clears the request (tests; a run that handled it).
void clear_stop_request();

// Thrown by throw_if_stop_requested(): the set-up of a run was stopped by `signal`. Deliberately
// not a std::exception, so that no `catch (const std::exception&)` turns a stop into a failure;
// the run driver, the ensemble and the stepper study catch it.
struct StopRequested {
  int signal = 0;
};
// The poll of long set-up loops: throws StopRequested after SIGINT/SIGTERM.
void throw_if_stop_requested();

// While armed, a stop request that no poll has acted on within `grace` (the work at hand has no
// poll: a neighbour build, a large allocation) ends the process from a helper thread:
// on_forced_stop(signal) (e.g. finish the run record), then std::_Exit(128 + signal). Disarming
// waits for a forced stop in progress, so the caller and the watchdog never both act. Arming
// counts: runs set up side by side (run/concurrent_jobs.hpp) each arm once and disarm once; the
// watchdog is armed while any of them is in its set-up (a disarm without an arm does nothing).
class SetupWatchdog {
 public:
  using OnForcedStop = std::function<void(int signal)>;
  explicit SetupWatchdog(OnForcedStop on_forced_stop,
                         std::chrono::milliseconds grace = std::chrono::milliseconds(300));
  ~SetupWatchdog();
  SetupWatchdog(const SetupWatchdog&) = delete;
  SetupWatchdog& operator=(const SetupWatchdog&) = delete;
  void arm();
  void disarm();

 private:
  void watch();

  OnForcedStop on_forced_stop_;
  std::chrono::milliseconds grace_;
  std::mutex mutex_;
  std::condition_variable wake_;
  int armed_ = 0;  // runs in their set-up
  bool quit_ = false;
  std::thread thread_;
};

}  // namespace sphark
