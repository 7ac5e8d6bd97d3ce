// The tree's Newtonian near-field kernel alone (f += m (x_a - x_b) / r^3, p += m / r over 800
// particles in L1, four lanes, AVX2 + FMA), with four ways to get 1/r:
//   sqrt_div      1 / sqrt(r^2), the four-lane square root and divide (what the tree uses);
//   newton3       the single-precision estimate and three double Newton steps (used before);
//   float_newton_halley  a float Newton step, then one third-order double step;
//   float_newton  the single-precision estimate and one float Newton step widened to double
//                 (relative error of 1/r about 3e-7: single precision; not used);
//   sqrt_only, div_only, floor   where the time goes: sqrt(r^2) alone, 1 / r^2 alone, and no
//                 inverse at all (r^2 in place of 1/r: the loads, sums and products alone);
//   alternating_sqrt_div_newton3  sqrt_div and newton3 on alternate vectors (faster, not used:
//                 a pair would get different bits from its two sides).
// Counter: ns_per_pair (times the clock in GHz: cycles per pair).
//   build/bin/bench_gravity_inverse_sqrt
#include <benchmark/benchmark.h>
#include <immintrin.h>

#include <random>
#include <vector>

namespace {

enum class Method { SqrtDiv, Newton3, FloatNewtonHalley, FloatNewton, SqrtOnly, DivOnly, Floor };

template <Method M>
__attribute__((target("avx2,fma"))) inline __m256d inverse_r(__m256d r2) {
  if constexpr (M == Method::SqrtDiv) return _mm256_div_pd(_mm256_set1_pd(1), _mm256_sqrt_pd(r2));
  if constexpr (M == Method::SqrtOnly) return _mm256_sqrt_pd(r2);
  if constexpr (M == Method::DivOnly) return _mm256_div_pd(_mm256_set1_pd(1), r2);
  if constexpr (M == Method::Floor) return r2;
  if constexpr (M == Method::FloatNewton) {
    const __m128 rf = _mm256_cvtpd_ps(r2);
    const __m128 yf = _mm_rsqrt_ps(rf);
    return _mm256_cvtps_pd(
        _mm_mul_ps(yf, _mm_fnmadd_ps(_mm_mul_ps(_mm_mul_ps(_mm_set1_ps(0.5f), rf), yf), yf, _mm_set1_ps(1.5f))));
  }
  if constexpr (M == Method::Newton3) {
    __m256d y = _mm256_cvtps_pd(_mm_rsqrt_ps(_mm256_cvtpd_ps(r2)));
    const __m256d half_r2 = _mm256_mul_pd(_mm256_set1_pd(0.5), r2), three_halves = _mm256_set1_pd(1.5);
    for (int k = 0; k < 3; ++k) y = _mm256_mul_pd(y, _mm256_fnmadd_pd(_mm256_mul_pd(half_r2, y), y, three_halves));
    return y;
  }
  if constexpr (M == Method::FloatNewtonHalley) {
    const __m128 rf = _mm256_cvtpd_ps(r2);
    __m128 yf = _mm_rsqrt_ps(rf);
    yf = _mm_mul_ps(yf, _mm_fnmadd_ps(_mm_mul_ps(_mm_mul_ps(_mm_set1_ps(0.5f), rf), yf), yf, _mm_set1_ps(1.5f)));
    const __m256d y = _mm256_cvtps_pd(yf);
    const __m256d e = _mm256_fnmadd_pd(_mm256_mul_pd(r2, y), y, _mm256_set1_pd(1));  // 1 - r^2 y^2
    return _mm256_mul_pd(y, _mm256_fmadd_pd(e, _mm256_fmadd_pd(e, _mm256_set1_pd(0.375), _mm256_set1_pd(0.5)),
                                            _mm256_set1_pd(1)));
  }
}

template <Method M>
__attribute__((target("avx2,fma"))) inline void step(const double* x, const double* y, const double* z,
                                                     const double* m, int b, __m256d X, __m256d Y, __m256d Z,
                                                     __m256d acc[4]) {
    const __m256d dx = _mm256_sub_pd(X, _mm256_loadu_pd(x + b)), dy = _mm256_sub_pd(Y, _mm256_loadu_pd(y + b));
    const __m256d dz = _mm256_sub_pd(Z, _mm256_loadu_pd(z + b));
    const __m256d inv_r = inverse_r<M>(_mm256_fmadd_pd(dx, dx, _mm256_fmadd_pd(dy, dy, _mm256_mul_pd(dz, dz))));
    const __m256d m_r = _mm256_mul_pd(_mm256_loadu_pd(m + b), inv_r), c = _mm256_mul_pd(m_r, _mm256_mul_pd(inv_r, inv_r));
    acc[0] = _mm256_fmadd_pd(c, dx, acc[0]), acc[1] = _mm256_fmadd_pd(c, dy, acc[1]);
    acc[2] = _mm256_fmadd_pd(c, dz, acc[2]), acc[3] = _mm256_add_pd(acc[3], m_r);
}

template <Method M, Method M2 = M>
__attribute__((target("avx2,fma"), noinline)) double sweep(const std::vector<double>* p, const double xa[3]) {
  const double *x = p[0].data(), *y = p[1].data(), *z = p[2].data(), *m = p[3].data();
  const auto n = static_cast<int>(p[0].size());
  __m256d acc[4] = {_mm256_setzero_pd(), _mm256_setzero_pd(), _mm256_setzero_pd(), _mm256_setzero_pd()};
  const __m256d X = _mm256_set1_pd(xa[0]), Y = _mm256_set1_pd(xa[1]), Z = _mm256_set1_pd(xa[2]);
  for (int b = 0; b + 8 <= n; b += 8) {
    step<M>(x, y, z, m, b, X, Y, Z, acc);
    step<M2>(x, y, z, m, b + 4, X, Y, Z, acc);
  }
  alignas(32) double out[4];
  _mm256_store_pd(out, _mm256_add_pd(_mm256_add_pd(acc[0], acc[1]), _mm256_add_pd(acc[2], acc[3])));
  return out[0] + out[1] + out[2] + out[3];
}

template <Method M, Method M2 = M>
void BM_NearKernel(benchmark::State& state) {
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) {
    state.SkipWithError("this CPU has no AVX2 + FMA");
    return;
  }
  constexpr int n = 800;
  std::vector<double> p[4];
  std::mt19937_64 g(1);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < n; ++i) p[0].push_back(u(g)), p[1].push_back(u(g)), p[2].push_back(u(g)), p[3].push_back(1);
  double xa[3] = {0.1, 0.2, 0.3};
  for (auto _ : state) {
    xa[0] += 1e-12;  // a new particle each time: nothing to hoist
    benchmark::DoNotOptimize(xa);
    benchmark::DoNotOptimize(sweep<M, M2>(p, xa));
  }
  state.counters["ns_per_pair"] = benchmark::Counter(static_cast<double>(n) * 1e-9,
                                                     benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(BM_NearKernel<Method::SqrtDiv>)->Name("BM_NearKernel/sqrt_div");
BENCHMARK(BM_NearKernel<Method::Newton3>)->Name("BM_NearKernel/newton3");
BENCHMARK(BM_NearKernel<Method::FloatNewtonHalley>)->Name("BM_NearKernel/float_newton_halley");
BENCHMARK(BM_NearKernel<Method::FloatNewton>)->Name("BM_NearKernel/float_newton");
BENCHMARK(BM_NearKernel<Method::SqrtOnly>)->Name("BM_NearKernel/sqrt_only");
BENCHMARK(BM_NearKernel<Method::DivOnly>)->Name("BM_NearKernel/div_only");
BENCHMARK(BM_NearKernel<Method::Floor>)->Name("BM_NearKernel/floor");
BENCHMARK(BM_NearKernel<Method::SqrtDiv, Method::Newton3>)->Name("BM_NearKernel/alternating_sqrt_div_newton3");
BENCHMARK_MAIN();
