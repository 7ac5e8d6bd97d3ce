#include "sphark/run/signals.hpp"

#include <atomic>
#include <csignal>
#include <cstdlib>

namespace sphark {
namespace {

std::atomic<int> g_stop{0};
static_assert(std::atomic<int>::is_always_lock_free, "the stop flag is written by a signal handler");

extern "C" void on_stop_signal(int sig) {
  int none = 0;
  g_stop.compare_exchange_strong(none, sig);  // the first signal is kept
}

}  // namespace

void install_stop_handlers() {
  struct sigaction sa {};
  sa.sa_handler = &on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

int stop_requested() { return g_stop.load(std::memory_order_relaxed); }

void clear_stop_request() { g_stop.store(0); }

void throw_if_stop_requested() {
  if (const int sig = stop_requested()) throw StopRequested{sig};
}

SetupWatchdog::SetupWatchdog(OnForcedStop on_forced_stop, std::chrono::milliseconds grace)
    : on_forced_stop_(std::move(on_forced_stop)), grace_(grace), thread_([this] { watch(); }) {}

SetupWatchdog::~SetupWatchdog() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void SetupWatchdog::arm() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++armed_;
  }
  wake_.notify_all();
}

void SetupWatchdog::disarm() {
  std::lock_guard<std::mutex> lock(mutex_);  // blocks while a forced stop is under way (it never returns)
  if (armed_ > 0) --armed_;
}

// Polls the flag every 20 ms while armed; a request older than grace_ while still armed ends the
// process (the lock is held from the decision to _Exit: disarm() cannot slip in between).
void SetupWatchdog::watch() {
  using Clock = std::chrono::steady_clock;
  std::unique_lock<std::mutex> lock(mutex_);
  Clock::time_point seen{};
  while (!quit_) {
    wake_.wait_for(lock, std::chrono::milliseconds(20));
    const int sig = stop_requested();
    if (armed_ == 0 || sig == 0) {
      seen = {};
      continue;
    }
    if (seen == Clock::time_point{}) seen = Clock::now();
    if (Clock::now() - seen < grace_) continue;
    if (on_forced_stop_) on_forced_stop_(sig);
    std::_Exit(128 + sig);
  }
}

}  // namespace sphark
