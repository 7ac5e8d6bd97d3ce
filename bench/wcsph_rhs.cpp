// WCSPH (+ velocity cleaning) right-hand side on the water-drop lattice: ns per particle per
// RHS call and pair interactions per second, N = 10^3 .. 10^6 (2D). Single-thread rows report
// CPU time, 2-thread rows wall time (UseRealTime); the shuffled row starts from the particles in
// random order. Run: build/bin/bench_wcsph_rhs
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "sphark/neighbours/neighbour_search.hpp"
#include "sphark/scenes/water_drop/water_drop.hpp"

using namespace sphark;

// The drop's state with its particles in random order (what a long flow does to the lattice
// order): every per-particle field permuted alike.
void shuffle_particles(WaterDrop& drop) {
  const StateLayout& L = drop.model->layout();
  const std::size_t n = L.particles();
  std::vector<std::size_t> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937_64(3));
  std::vector<Real> y = drop.y0;
  for (Field f : {Field::Position, Field::Velocity, Field::Density, Field::Psi}) {
    if (!L.has(f)) continue;
    const std::size_t o = L.offset(f), c = L.field_size(f) / n;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < c; ++k) y[o + c * i + k] = drop.y0[o + c * perm[i] + k];
  }
  drop.y0 = y;
}

static void BM_WcsphRhs(benchmark::State& state) {
  WaterDropConfig cfg;
  cfg.radius = std::sqrt(static_cast<Real>(state.range(0)) * cfg.spacing * cfg.spacing / kPi);
  cfg.cleaning = state.range(1) != 0;
  omp_set_num_threads(static_cast<int>(state.range(2)));
  WaterDrop drop = make_water_drop(cfg);
  if (state.range(3) != 0) shuffle_particles(drop);
  OdeSystem& sys = drop.model->system();
  std::vector<Real> ydot(drop.y0.size());
  sys.rhs(0, drop.y0.data(), ydot.data());  // first call builds the lists
  for (auto _ : state) {
    sys.rhs(0, drop.y0.data(), ydot.data());
    benchmark::DoNotOptimize(ydot.data());
  }
  // pairs: ordered pairs closer than the kernel support 2h (counted on the initial positions)
  const Real h = cfg.h_factor * cfg.spacing;
  const auto x = vector_field<2>(drop.y0.data(), drop.model->layout(), Field::Position);
  NeighbourSearch<2> ns;
  ns.build(x.data(), drop.particles(), 2 * h);
  const Real pairs_per_particle = static_cast<Real>(ns.list().pairs()) / static_cast<Real>(drop.particles());
  const auto n = static_cast<double>(drop.particles());
  state.counters["ns_per_particle"] =
      benchmark::Counter(n * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["pairs_per_s"] = benchmark::Counter(n * pairs_per_particle, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["particles"] = n;
  state.counters["pairs_per_particle"] = pairs_per_particle;
  state.counters["threads"] = static_cast<double>(state.range(2));
  state.counters["shuffled"] = static_cast<double>(state.range(3));
}
BENCHMARK(BM_WcsphRhs)
    ->ArgNames({"n", "clean", "threads", "shuffled"})
    ->Args({1000, 1, 1, 0})
    ->Args({10000, 0, 1, 0})
    ->Args({10000, 1, 1, 0})
    ->Args({100000, 1, 1, 0})
    ->Args({100000, 1, 1, 1})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WcsphRhs)->ArgNames({"n", "clean", "threads", "shuffled"})->Args({1000000, 1, 1, 0})->Iterations(3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WcsphRhs)->ArgNames({"n", "clean", "threads", "shuffled"})->Args({100000, 1, 2, 0})->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WcsphRhs)->ArgNames({"n", "clean", "threads", "shuffled"})->Args({1000000, 1, 2, 0})->Iterations(3)
    ->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
