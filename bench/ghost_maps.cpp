// Cost of one ghost-map evaluation (seed 004, §6 / Table 1): mirror, cylinder (eq. 21), sphere
// (eq. 25, fast cube root vs std::cbrt), torus (eq. 28: the library's robust root, Viete's form
// only, and the Appendix A formula (41)-(47) literally, with complex arithmetic).
#include <benchmark/benchmark.h>

#include <cmath>
#include <complex>
#include <random>
#include <vector>

#include "sphark/boundaries/maps.hpp"

using namespace sphark;

namespace {

std::vector<Real> random_s(std::size_t n, Real depth) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<Real> U(-depth, 0);
  std::vector<Real> s(n);
  for (auto& e : s) e = U(rng);
  return s;
}
std::vector<Real> random_cos(std::size_t n) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<Real> U(-kPi, kPi);
  std::vector<Real> c(n);
  for (auto& e : c) e = std::cos(U(rng));
  return c;
}

// seed 004, Appendix A, eqs. (41)-(47) as printed: z = (-1 + i sqrt3)/2, p = 12 x Bu^2 - 1,
// Delta = cbrt(p + sqrt(p^2 - 1)), g+^-1 = (1/Delta + Delta - 1)/(2 Bu), g-^-1 = Re[(conj(z)/Delta
// + z Delta - 1)/(2 Bu)], g0^-1 = sqrt(2x). Loses digits as Bu -> 0 (0/0), kept for timing only.
Real paper_torus_inverse(Real x, Real Bu) {
  using C = std::complex<Real>;
  if (Bu == 0) return std::sqrt(2 * x);
  const C z(-0.5, std::sqrt(3.0) / 2);
  const C p(12 * x * Bu * Bu - 1, 0);
  const C delta = std::pow(p + std::sqrt(p * p - 1.0), 1.0 / 3.0);
  if (Bu > 0) return std::real((1.0 / delta + delta - 1.0) / (2 * Bu));
  return std::real((std::conj(z) / delta + z * delta - 1.0) / (2 * Bu));
}

constexpr std::size_t kN = 4096;

void BM_Mirror(benchmark::State& st) {
  const auto s = random_s(kN, 0.3);
  for (auto _ : st)
    for (Real e : s) benchmark::DoNotOptimize(mirror_map(e).psi);
  st.SetItemsProcessed(st.iterations() * kN);
}
void BM_Cylinder(benchmark::State& st) {
  const auto s = random_s(kN, 0.3);
  for (auto _ : st)
    for (Real e : s) benchmark::DoNotOptimize(cylinder_map(e, 1, FluidSide::Inside).psi);
  st.SetItemsProcessed(st.iterations() * kN);
}
void BM_Sphere(benchmark::State& st) {
  const auto s = random_s(kN, 0.3);
  for (auto _ : st)
    for (Real e : s) benchmark::DoNotOptimize(sphere_map(e, 1, FluidSide::Inside).psi);
  st.SetItemsProcessed(st.iterations() * kN);
}
void BM_SphereStdCbrt(benchmark::State& st) {
  const auto s = random_s(kN, 0.3);
  for (auto _ : st)
    for (Real e : s) benchmark::DoNotOptimize(std::cbrt(2 - (1 + e) * (1 + e) * (1 + e)) - 1);
  st.SetItemsProcessed(st.iterations() * kN);
}
void BM_Torus(benchmark::State& st) {
  const auto s = random_s(kN, 0.3);
  const auto c = random_cos(kN);
  for (auto _ : st)
    for (std::size_t i = 0; i < kN; ++i) benchmark::DoNotOptimize(torus_map(s[i], 1, 3, c[i], FluidSide::Inside).psi);
  st.SetItemsProcessed(st.iterations() * kN);
}
// Torus R/a = 3 at inner coordinate s and cos u: B_u and the right-hand side c of the cubic.
struct TorusInput {
  Real Bu, cc;
};
TorusInput torus_input(Real s, Real cos_u) {
  const Real Bu = cos_u / 3, rho = 1 + s;
  return {Bu, 2 * (Bu / 3 + 0.5) - rho * rho * (Bu * rho / 3 + 0.5)};
}
void BM_TorusVieteOnly(benchmark::State& st) {
  const auto s = random_s(kN, 0.3);
  const auto c = random_cos(kN);
  for (auto _ : st)
    for (std::size_t i = 0; i < kN; ++i) {
      const auto [Bu, cc] = torus_input(s[i], c[i]);
      const Real r = std::sqrt(2 * cc);
      benchmark::DoNotOptimize(r / depressed_cubic_root((2.0 / 3.0) * Bu * r) - 1);
    }
  st.SetItemsProcessed(st.iterations() * kN);
}
void BM_TorusPaperAppendix(benchmark::State& st) {
  const auto s = random_s(kN, 0.3);
  const auto c = random_cos(kN);
  for (auto _ : st)
    for (std::size_t i = 0; i < kN; ++i) {
      const auto [Bu, cc] = torus_input(s[i], c[i]);
      benchmark::DoNotOptimize(paper_torus_inverse(cc, Bu) - 1);
    }
  st.SetItemsProcessed(st.iterations() * kN);
}

}  // namespace

BENCHMARK(BM_Mirror);
BENCHMARK(BM_Cylinder);
BENCHMARK(BM_Sphere);
BENCHMARK(BM_SphereStdCbrt);
BENCHMARK(BM_Torus);
BENCHMARK(BM_TorusVieteOnly);
BENCHMARK(BM_TorusPaperAppendix);
BENCHMARK_MAIN();
