// Neighbour-list build (cell grid, periodic box) at the list radius the SPMHD scheme uses,
// 2 h (1 + skin) with h = 1.2 dx: 2D square lattice N = 10^3 .. 10^6 and a 3D cubic lattice,
// jittered by 0.1 dx. Reports ns per particle per build and listed pairs per second.
//   build/bin/bench_neighbours --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <random>

#include "sphark/neighbours/neighbour_search.hpp"

using namespace sphark;

namespace {
template <int D>
void BM_Build(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  const int nx = static_cast<int>(std::lround(std::pow(static_cast<double>(state.range(0)), 1.0 / D)));
  std::size_t n = 1;
  for (int k = 0; k < D; ++k) n *= static_cast<std::size_t>(nx);
  const Real dx = 1.0 / nx;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<Real> jitter(-0.05 * dx, 0.05 * dx);
  std::vector<Real> x(D * n);
  for (std::size_t a = 0; a < n; ++a) {
    std::size_t rest = a;
    for (int k = 0; k < D; ++k) {
      x[D * a + k] = (rest % nx + 0.5) * dx + jitter(rng);
      rest /= nx;
    }
  }
  PeriodicBox<D> box;
  box.periodic.fill(true);
  NeighbourSearch<D> ns(box);
  const Real radius = 2 * 1.2 * dx * 1.25;
  ns.build(x.data(), n, radius);
  for (auto _ : state) {
    ns.build(x.data(), n, radius);
    benchmark::DoNotOptimize(ns.list().indices.data());
  }
  const auto nd = static_cast<double>(n);
  state.counters["ns_per_particle"] =
      benchmark::Counter(nd * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["pairs_per_s"] =
      benchmark::Counter(static_cast<double>(ns.list().pairs()), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["pairs_per_particle"] = static_cast<double>(ns.list().pairs()) / nd;
  state.counters["particles"] = nd;
  state.counters["threads"] = omp_get_max_threads();
  state.counters["allocating_builds"] = static_cast<double>(ns.allocations());
}
}  // namespace

BENCHMARK(BM_Build<2>)->ArgNames({"n", "threads"})->Args({1000, 1})->Args({10000, 1})->Args({100000, 1})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Build<2>)->ArgNames({"n", "threads"})->Args({1000000, 1})->Iterations(3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Build<2>)->ArgNames({"n", "threads"})->Args({100000, 2})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Build<3>)->ArgNames({"n", "threads"})->Args({27000, 1})->Args({125000, 1})->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
