// The machine's ceilings for the roofline table of docs/performance.md, on one core:
//   BM_PeakFma   the floating-point peak of the pair loops' instruction set: independent AVX2 FMA
//                chains on four doubles (2 flops per lane), flops per second
//   BM_Triad     memory bandwidth, STREAM's triad a[i] = b[i] + s c[i] over arrays far larger
//                than the caches (24 bytes moved per element, 32 with the write-allocate of a)
// Run: build/bin/bench_roofline
#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

#include "sphark/simd/lanes.hpp"

#pragma GCC diagnostic ignored "-Wpsabi"

namespace {

using sphark::simd::Real4;

constexpr int kChains = 12;  // enough independent FMAs to cover the latency of two FMA units

#if defined(SPHARK_SIMD_HAVE_AVX2)
__attribute__((target("avx2,fma"), noipa)) double fma_chains(long iterations) {
  Real4 acc[kChains];
  for (int c = 0; c < kChains; ++c) acc[c] = Real4{} + 1e-3 * c;
  const Real4 m = Real4{} + 0.999999, a = Real4{} + 1e-9;
  for (long i = 0; i < iterations; ++i)
    for (int c = 0; c < kChains; ++c) acc[c] = __builtin_ia32_vfmaddpd256(acc[c], m, a);
  Real4 s{};
  for (int c = 0; c < kChains; ++c) s += acc[c];
  return s[0] + s[1] + s[2] + s[3];
}
#endif

void BM_PeakFma(benchmark::State& state) {
#if defined(SPHARK_SIMD_HAVE_AVX2)
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) {
    state.SkipWithError("no AVX2 + FMA on this CPU");
    return;
  }
  const long iterations = 1 << 22;
  for (auto _ : state) benchmark::DoNotOptimize(fma_chains(iterations));
  state.counters["flops_per_s"] =
      benchmark::Counter(2.0 * 4 * kChains * static_cast<double>(iterations), benchmark::Counter::kIsIterationInvariantRate);
#else
  state.SkipWithError("x86-64 only");
#endif
}
BENCHMARK(BM_PeakFma)->Unit(benchmark::kMillisecond);

void BM_Triad(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  std::vector<double> a(n, 0), b(n, 1), c(n, 2);
  const double s = 3;
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.counters["bytes_per_s"] = benchmark::Counter(24.0 * static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes_per_s_with_write_allocate"] =
      benchmark::Counter(32.0 * static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Triad)->Arg(1 << 24)->Unit(benchmark::kMillisecond);  // 3 x 128 MiB

}  // namespace

BENCHMARK_MAIN();
