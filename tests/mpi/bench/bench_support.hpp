#pragma once
// Google Benchmark under mpirun: every rank runs every benchmark with a fixed iteration count
// (collectives stay in step), the time of an iteration is the slowest rank's (manual time), and
// only rank 0 reports. Timing programs for docs/scaling.md, not tests.
#include <benchmark/benchmark.h>

#include <chrono>
#include <random>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/parallel/mpi_session.hpp"

namespace sphark::bench {

const Communicator& world();

// Runs f once; the iteration time is the maximum over the ranks (barrier before).
template <class F>
void timed(benchmark::State& state, F&& f) {
  world().barrier();
  const auto start = std::chrono::steady_clock::now();
  f();
  const double mine = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  state.SetIterationTime(world().allreduce(mine, ReduceOp::Max));
}

// n uniform random points in [0, 1)^D (D per point), different on every rank.
template <int D>
std::vector<Real> random_points(std::size_t n, unsigned salt = 0) {
  std::mt19937_64 gen(1234567 + 7919 * world().rank() + salt);
  std::uniform_real_distribution<Real> u(0, 1);
  std::vector<Real> x(D * n);
  for (Real& v : x) v = u(gen);
  return x;
}

inline std::size_t local_share(std::size_t total) { return total / world().size(); }

}  // namespace sphark::bench

// main(): MPI session, benchmarks, silent ranks > 0.
#define SPHARK_MPI_BENCH_MAIN()                                                            \
  namespace sphark::bench {                                                                \
  const MpiSession* g_session = nullptr;                                                   \
  const Communicator& world() { return g_session->world(); }                               \
  class Silent : public benchmark::BenchmarkReporter {                                     \
   public:                                                                                 \
    bool ReportContext(const Context&) override { return true; }                           \
    void ReportRuns(const std::vector<Run>&) override {}                                   \
  };                                                                                       \
  }                                                                                        \
  int main(int argc, char** argv) {                                                        \
    sphark::MpiSession session(argc, argv);                                                \
    sphark::bench::g_session = &session;                                                   \
    benchmark::Initialize(&argc, argv);                                                    \
    return session.run([](const sphark::Communicator& w) {                                 \
      sphark::bench::Silent silent;                                                        \
      if (w.rank() == 0) benchmark::RunSpecifiedBenchmarks();                              \
      else benchmark::RunSpecifiedBenchmarks(&silent);                                     \
      benchmark::Shutdown();                                                               \
      return 0;                                                                            \
    });                                                                                    \
  }
