// Self-gravity cost per particle: tree (theta = 0.5, quadrupoles, mutual walk) and direct
// summation, N = 1e2 .. 1e6 (direct to 3e4), on a uniform sphere and a rho ~ 1/r sphere (random placement,
// h = 1.2 (m / rho)^(1/3) from the exact density). Counters: ns per particle per call, and for
// the tree ns / (particle log2 N) (flat if the cost is N log N), far (cell-cell) interactions
// and near particle pairs per particle. Single-thread rows report CPU time; 2-thread rows wall
// time (UseRealTime). Compare with bench_spmhd_rhs (3D row) run in the same session.
// BM_TreeBuild: the tree's build alone, afresh against a rebuild from the last build's order.
//   build/bin/bench_gravity --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "sphark/gravity/direct_gravity.hpp"
#include "sphark/gravity/force_errors.hpp"
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

// Near particle pairs (ordered, evaluated directly) and far interactions per particle.
void set_pair_counters(benchmark::State& state, const TreeGravity<CubicSpline<3>>& tree, std::size_t n) {
  std::size_t near_pairs = 0;
  const auto& nodes = tree.tree().nodes();
  for (std::uint32_t leaf : tree.tree().leaves())
    for (std::uint32_t k = tree.walk().near().begin(leaf); k < tree.walk().near().end(leaf); ++k)
      near_pairs += static_cast<std::size_t>(nodes[leaf].count()) *
                    nodes[tree.walk().near().partner[k] & ~DualTreeWalk::kNewtonian].count();
  state.counters["far_per_particle"] = 2.0 * tree.walk().far_pairs() / static_cast<double>(n);
  state.counters["near_per_particle"] = static_cast<double>(near_pairs) / static_cast<double>(n);
}

// args: n, threads, profile (0 uniform, 1 1/r), leaf size, simd (0: SSE2 loops instead of AVX2),
// opening (0 fixed, 1 mass; each at its default angle)
void BM_TreeGravity(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  use_gravity_avx2(state.range(4) != 0);
  const SphereParticles& p = sphere(static_cast<SphereProfile>(state.range(2)), static_cast<std::size_t>(state.range(0)));
  GravityOptions opt;
  opt.leaf_size = static_cast<int>(state.range(3));
  opt.opening = state.range(5) ? GravityOpening::Mass : GravityOpening::Fixed;
  opt.theta = default_theta(opt.opening);
  TreeGravity<CubicSpline<3>> tree(opt);
  std::vector<Real> acc(3 * p.size()), pot(p.size());
  tree.compute(p.sources(), acc.data(), pot.data());  // buffers sized
  for (auto _ : state) {
    benchmark::DoNotOptimize(tree.compute(p.sources(), acc.data(), pot.data()));
    benchmark::ClobberMemory();
  }
  set_counters(state, p.size());
  set_pair_counters(state, tree, p.size());
  state.counters["allocations"] = static_cast<double>(tree.allocations());
  state.counters["avx2"] = gravity_simd() == "avx2";
  use_gravity_avx2(true);
}

// Accuracy is measured on a sample: every (n / kSample)-th particle, whose direct-summation
// accelerations (O(kSample N)) are computed once per set (both threads).
constexpr std::size_t kSample = 4000;

std::vector<std::size_t> sample_of(std::size_t n) {
  std::vector<std::size_t> s;
  for (std::size_t k = 0; k < std::min(n, kSample); ++k) s.push_back(k * n / std::min(n, kSample));
  return s;
}

const std::vector<Real>& direct_sample(SphereProfile profile, std::size_t n) {
  static std::map<std::pair<int, std::size_t>, std::vector<Real>> cache;
  const auto key = std::make_pair(static_cast<int>(profile), n);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  omp_set_num_threads(2);
  const SphereParticles& p = sphere(profile, n);
  const std::vector<std::size_t> sample = sample_of(n);
  std::vector<Real> acc(3 * sample.size()), pot(sample.size());
  const auto ns = static_cast<std::ptrdiff_t>(sample.size());
#pragma omp parallel for schedule(dynamic, 8)
  for (std::ptrdiff_t k = 0; k < ns; ++k)
    direct_field_at<CubicSpline<3>>(p.sources(), sample[k], 1, &acc[3 * k], &pot[k]);
  return cache.emplace(key, std::move(acc)).first->second;
}

// Fixed against mass-dependent opening at equal accuracy, one thread. args: n, profile,
// opening (0 fixed, 1 mass), theta (fixed) or theta_0 (mass) in hundredths, leaf size. Counters: near
// particle pairs and far interactions per particle, the median and 99th-percentile relative
// force error against direct summation on the sample.
void BM_TreeOpening(benchmark::State& state) {
  const auto profile = static_cast<SphereProfile>(state.range(1));
  const auto n = static_cast<std::size_t>(state.range(0));
  const std::vector<Real>& direct = direct_sample(profile, n);
  omp_set_num_threads(1);
  const SphereParticles& p = sphere(profile, n);
  GravityOptions opt;
  opt.opening = state.range(2) ? GravityOpening::Mass : GravityOpening::Fixed;
  opt.theta = static_cast<Real>(state.range(3)) / 100;
  opt.leaf_size = static_cast<int>(state.range(4));
  TreeGravity<CubicSpline<3>> tree(opt);
  std::vector<Real> acc(3 * n), pot(n);
  tree.compute(p.sources(), acc.data(), pot.data());
  for (auto _ : state) {
    benchmark::DoNotOptimize(tree.compute(p.sources(), acc.data(), pot.data()));
    benchmark::ClobberMemory();
  }
  set_counters(state, n);
  set_pair_counters(state, tree, n);
  std::vector<Real> sampled;
  for (std::size_t k : sample_of(n)) sampled.insert(sampled.end(), &acc[3 * k], &acc[3 * k + 3]);
  const std::vector<Real> e = relative_force_errors(sampled.data(), direct.data(), direct.size() / 3);
  state.counters["median_error"] = quantile(e, 0.5);
  state.counters["p99_error"] = quantile(e, 0.99);
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

// The tree's build alone, one thread: args n, warm (1: every build alternates between two
// position sets 1e-3 of the radius apart, as between the events of a block-step run, so each
// rebuild starts from the last order; 0: a fresh tree object every build).
void BM_TreeBuild(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const bool warm = state.range(1) != 0;
  const SphereParticles& a = sphere(SphereProfile::InverseR, n);
  SphereParticles b = a;
  for (std::size_t k = 0; k < b.x.size(); ++k) b.x[k] += 1e-3 * std::sin(static_cast<double>(7 * k));
  omp_set_num_threads(1);
  GravityTree tree;
  long builds = 0;
  for (auto _ : state) {
    if (!warm) tree = GravityTree{};
    tree.build((builds++ % 2 ? b : a).sources(), 2, GravityOptions{}.leaf_size);
    benchmark::DoNotOptimize(tree.nodes().data());
  }
  set_counters(state, n);
}

void tree_args(benchmark::internal::Benchmark* b, int threads) {
  b->ArgNames({"n", "threads", "profile", "leaf", "simd", "opening"});
  const GravityOptions o;
  for (int opening : {0, 1})
    for (int profile : {0, 1})
      for (long n : {100L, 300L, 1000L, 3000L, 10000L, 30000L, 100000L, 300000L, 1000000L})
        b->Args({n, threads, profile, o.leaf_size, 1, opening});
}
void direct_args(benchmark::internal::Benchmark* b, int threads) {
  b->ArgNames({"n", "threads", "profile"});
  for (int profile : {0, 1})
    for (long n : {100L, 300L, 1000L, 3000L, 10000L, 30000L}) b->Args({n, threads, profile});
}

}  // namespace

BENCHMARK(BM_TreeGravity)->Apply([](auto* b) { tree_args(b, 1); })->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TreeGravity)->Apply([](auto* b) { tree_args(b, 2); })->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TreeBuild)->ArgNames({"n", "warm"})->ArgsProduct({{3000, 10000, 30000, 100000}, {0, 1}})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DirectGravity)->Apply([](auto* b) { direct_args(b, 1); })->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DirectGravity)->Apply([](auto* b) { direct_args(b, 2); })->UseRealTime()->Unit(benchmark::kMillisecond);
// leaf-size scan at N = 1e5 and 1e6 (uniform), one thread; SSE2 against AVX2 loops
BENCHMARK(BM_TreeGravity)->ArgNames({"n", "threads", "profile", "leaf", "simd", "opening"})
    ->ArgsProduct({{100000, 1000000}, {1}, {0}, {4, 6, 12}, {1}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TreeGravity)->ArgNames({"n", "threads", "profile", "leaf", "simd", "opening"})
    ->ArgsProduct({{100000, 1000000}, {1}, {0}, {8}, {0}, {0, 1}})->Unit(benchmark::kMillisecond);
// Opening criteria at equal accuracy: fixed theta 0.4 .. 0.6 against theta(M) with theta_0
// 0.25 .. 0.45, N = 3e4 .. 1e6, both profiles (the sampled direct reference: ~10 s at 1e6).
BENCHMARK(BM_TreeOpening)->ArgNames({"n", "profile", "opening", "theta", "leaf"})
    ->ArgsProduct({{30000, 100000, 1000000}, {0, 1}, {0}, {40, 45, 50, 55, 60}, {8}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TreeOpening)->ArgNames({"n", "profile", "opening", "theta", "leaf"})
    ->ArgsProduct({{30000, 100000, 1000000}, {0, 1}, {1}, {25, 30, 35, 40, 45}, {4, 6, 8, 12}})->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
