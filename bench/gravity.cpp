// Self-gravity cost per particle: tree (theta = 0.5, quadrupoles, mutual walk) and direct
// summation, N = 1e2 .. 1e6 (direct to 3e4), on a uniform sphere and a rho ~ 1/r sphere (random placement,
// h = 1.2 (m / rho)^(1/3) from the exact density). Counters: ns per particle per call, and for
// the tree ns / (particle log2 N) (flat if the cost is N log N), far (cell-cell) interactions
// and near particle pairs per particle. Single-thread rows report CPU time; 2-thread rows wall
// time (UseRealTime). Compare with bench_spmhd_rhs (3D row) run in the same session.
//   build/bin/bench_gravity --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "sphark/gravity/sphere_particles.hpp"
#include "sphark/gravity/tree_gravity.hpp"
#include "sphark/kernels/kernels.hpp"

using namespace sphark;

namespace {

// One set of particles per (profile, n), made once.
const SphereParticles& sphere(SphereProfile profile, std::size_t n) {
  static std::map<std::pair<int, std::size_t>, SphereParticles> cache;
  const auto key = std::make_pair(static_cast<int>(profile), n);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, random_sphere(profile, n, 1, 1, 1.2, 7 + n)).first;
  return it->second;
}

void set_counters(benchmark::State& state, std::size_t n) {
  const auto nd = static_cast<double>(n);
  state.counters["ns_per_particle"] =
      benchmark::Counter(nd * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["ns_per_particle_log2N"] = benchmark::Counter(
      nd * std::log2(nd) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["particles"] = nd;
  state.counters["threads"] = omp_get_max_threads();
}

// args: n, threads, profile (0 uniform, 1 1/r), leaf size[, 0: SSE2 loops instead of AVX2]
void BM_TreeGravity(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  use_gravity_avx2(state.range(4) != 0);
  const SphereParticles& p = sphere(static_cast<SphereProfile>(state.range(2)), static_cast<std::size_t>(state.range(0)));
  GravityOptions opt;
  opt.leaf_size = static_cast<int>(state.range(3));
  TreeGravity<CubicSpline<3>> tree(opt);
  std::vector<Real> acc(3 * p.size()), pot(p.size());
  tree.compute(p.sources(), acc.data(), pot.data());  // buffers sized
  for (auto _ : state) {
    benchmark::DoNotOptimize(tree.compute(p.sources(), acc.data(), pot.data()));
    benchmark::ClobberMemory();
  }
  set_counters(state, p.size());
  std::size_t near_pairs = 0;  // ordered particle pairs evaluated directly
  const auto& nodes = tree.tree().nodes();
  for (std::uint32_t leaf : tree.tree().leaves())
    for (std::uint32_t k = tree.walk().near().begin(leaf); k < tree.walk().near().end(leaf); ++k)
      near_pairs += static_cast<std::size_t>(nodes[leaf].count()) *
                    nodes[tree.walk().near().partner[k] & ~DualTreeWalk::kNewtonian].count();
  state.counters["far_per_particle"] = 2.0 * tree.walk().far_pairs() / static_cast<double>(p.size());
  state.counters["near_per_particle"] = static_cast<double>(near_pairs) / static_cast<double>(p.size());
  state.counters["allocations"] = static_cast<double>(tree.allocations());
  state.counters["avx2"] = gravity_simd() == "avx2";
  use_gravity_avx2(true);
}

void BM_DirectGravity(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  const SphereParticles& p = sphere(static_cast<SphereProfile>(state.range(2)), static_cast<std::size_t>(state.range(0)));
  auto direct = make_self_gravity<CubicSpline<3>>(GravitySolver::Direct);
  std::vector<Real> acc(3 * p.size()), pot(p.size());
  for (auto _ : state) {
    benchmark::DoNotOptimize(direct->compute(p.sources(), acc.data(), pot.data()));
    benchmark::ClobberMemory();
  }
  set_counters(state, p.size());
}

void tree_args(benchmark::internal::Benchmark* b, int threads) {
  b->ArgNames({"n", "threads", "profile", "leaf", "simd"});
  const GravityOptions o;
  for (int profile : {0, 1})
    for (long n : {100L, 300L, 1000L, 3000L, 10000L, 30000L, 100000L, 300000L, 1000000L})
      b->Args({n, threads, profile, o.leaf_size, 1});
}
void direct_args(benchmark::internal::Benchmark* b, int threads) {
  b->ArgNames({"n", "threads", "profile"});
  for (int profile : {0, 1})
    for (long n : {100L, 300L, 1000L, 3000L, 10000L, 30000L}) b->Args({n, threads, profile});
}

}  // namespace

BENCHMARK(BM_TreeGravity)->Apply([](auto* b) { tree_args(b, 1); })->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TreeGravity)->Apply([](auto* b) { tree_args(b, 2); })->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DirectGravity)->Apply([](auto* b) { direct_args(b, 1); })->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DirectGravity)->Apply([](auto* b) { direct_args(b, 2); })->UseRealTime()->Unit(benchmark::kMillisecond);
// leaf-size scan at N = 1e5 and 1e6 (uniform), one thread; SSE2 against AVX2 loops
BENCHMARK(BM_TreeGravity)->ArgNames({"n", "threads", "profile", "leaf", "simd"})
    ->ArgsProduct({{100000, 1000000}, {1}, {0}, {4, 6, 12}, {1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TreeGravity)->ArgNames({"n", "threads", "profile", "leaf", "simd"})
    ->ArgsProduct({{100000, 1000000}, {1}, {0}, {8}, {0}})->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
