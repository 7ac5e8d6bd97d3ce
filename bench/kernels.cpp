// Kernel evaluation: W and (dW/dr)/r of every kernel of the list over q in [0, support) (2D and 3D), ns
// per evaluation (one W plus one f_over_r).
//   build/bin/bench_kernels
#include <benchmark/benchmark.h>

#include <vector>

#include "sphark/kernels/kernel_list.hpp"

using namespace sphark;

namespace {
template <class K>
void BM_Kernel(benchmark::State& state) {
  const std::size_t n = 4096;
  const Real h = 0.7;
  std::vector<Real> r(n);
  for (std::size_t i = 0; i < n; ++i) r[i] = K::support * h * (i + 0.5) / n;
  for (auto _ : state) {
    Real s = 0;
    for (std::size_t i = 0; i < n; ++i) s += K::w(r[i], h) + K::f_over_r(r[i], h);
    benchmark::DoNotOptimize(s);
  }
  state.counters["ns_per_eval"] = benchmark::Counter(static_cast<double>(n) * 1e-9,
                                                     benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
}
}  // namespace

#define SPHARK_KERNEL_BENCHMARKS(K) BENCHMARK(BM_Kernel<K<2>>); BENCHMARK(BM_Kernel<K<3>>);
SPHARK_KERNELS(SPHARK_KERNEL_BENCHMARKS)
BENCHMARK_MAIN();
