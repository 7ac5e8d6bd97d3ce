#include "sphark/run/concurrent_jobs.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "sphark/run/signals.hpp"

namespace sphark {

std::size_t run_concurrently(std::size_t count, int lanes, int threads_per_lane,
                             const std::function<bool(std::size_t)>& job) {
  std::atomic<std::size_t> next{0}, started{0};
  std::atomic<bool> halted{false};
  std::mutex error_mutex;
  std::exception_ptr error;
  auto lane = [&](bool own_thread) {
    const int saved_threads = omp_get_max_threads();
    omp_set_num_threads(std::max(1, threads_per_lane));  // this thread's teams (an OpenMP ICV per thread)
    for (std::size_t i = next++; i < count; i = next++) {
      if (stop_requested() || halted) break;
      ++started;
      try {
        if (!job(i)) halted = true;
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        halted = true;
      }
    }
    if (!own_thread) omp_set_num_threads(saved_threads);
  };
  const int n = static_cast<int>(std::clamp<std::size_t>(static_cast<std::size_t>(std::max(1, lanes)), 1, std::max<std::size_t>(count, 1)));
  std::vector<std::thread> others;
  for (int k = 1; k < n; ++k) others.emplace_back(lane, true);
  lane(false);
  for (std::thread& t : others) t.join();
  if (error) std::rethrow_exception(error);
  return started;
}

}  // namespace sphark
