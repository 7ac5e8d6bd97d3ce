// Cost of the seed 001 second-derivative operators: assemble the sparse matrix, apply it once,
// solve the boundary-value problem (5.18). Uniform particles, h = c dx (c = 2 for CSPM/ICSPM/BIM,
// and BIM with the paper's h = k^2 dx, k = log2((N-1)/10) + 1).
#include <benchmark/benchmark.h>

#include <cmath>

#include "sphark/derivatives1d/bvp1d.hpp"
#include "sphark/derivatives1d/study1d.hpp"

using namespace sphark;
using namespace sphark::d1;

namespace {

Real factor(bool k_squared, Index n) {
  if (!k_squared) return 2.0;
  const Real k = std::log2(static_cast<Real>(n - 1) / 10.0) + 1.0;
  return k * k;
}

template <Method M, bool KSquared>
void BM_Assemble(benchmark::State& state) {
  const Particles1D p = uniform_particles(state.range(0));
  const Real h = smoothing_length(p, factor(KSquared, p.size()));
  Index nnz = 0;
  for (auto _ : state) {
    SparseMatrix L = second_derivative(M, p, h);
    nnz = L.nonZeros();
    benchmark::DoNotOptimize(L.valuePtr());
  }
  state.counters["nnz"] = static_cast<double>(nnz);
  state.SetItemsProcessed(state.iterations() * p.size());
}

template <Method M, bool KSquared>
void BM_Apply(benchmark::State& state) {
  const Particles1D p = uniform_particles(state.range(0));
  const Real h = smoothing_length(p, factor(KSquared, p.size()));
  const SparseMatrix L = second_derivative(M, p, h);
  const Eigen::VectorXd f = p.x.unaryExpr(seed_function().f);
  Eigen::VectorXd y(p.size());
  for (auto _ : state) {
    y.noalias() = L * f;
    benchmark::DoNotOptimize(y.data());
  }
  state.SetItemsProcessed(state.iterations() * p.size());
}

template <Method M, bool KSquared>
void BM_SolveBvp(benchmark::State& state) {
  const Particles1D p = uniform_particles(state.range(0));
  const Real h = smoothing_length(p, factor(KSquared, p.size()));
  const TestFunction fn = seed_function();
  const Eigen::VectorXd g = p.x.unaryExpr(fn.f2);
  for (auto _ : state) {
    Eigen::VectorXd u = solve_dirichlet(second_derivative(M, p, h), p, g, fn.f(0.0), fn.f(1.0));
    benchmark::DoNotOptimize(u.data());
  }
  state.SetItemsProcessed(state.iterations() * p.size());
}

}  // namespace

// c = 2: N = 11 ... 81921 (the operator has a fixed ~7 entries per row)
BENCHMARK(BM_Assemble<Method::Cspm, false>)->RangeMultiplier(4)->Range(81, 81921)->Arg(1281);
BENCHMARK(BM_Assemble<Method::Icspm, false>)->RangeMultiplier(4)->Range(81, 81921)->Arg(1281);
BENCHMARK(BM_Assemble<Method::Bim, false>)->RangeMultiplier(4)->Range(81, 81921)->Arg(1281);
BENCHMARK(BM_Apply<Method::Cspm, false>)->RangeMultiplier(4)->Range(81, 81921);
BENCHMARK(BM_Apply<Method::Icspm, false>)->RangeMultiplier(4)->Range(81, 81921);
BENCHMARK(BM_SolveBvp<Method::Cspm, false>)->RangeMultiplier(4)->Range(81, 81921);
BENCHMARK(BM_SolveBvp<Method::Icspm, false>)->RangeMultiplier(4)->Range(81, 81921);
// the paper's BIM with h = k^2 dx: N = 11, 21, ..., 1281 (k = 1 ... 8)
BENCHMARK(BM_Assemble<Method::Bim, true>)->Arg(81)->Arg(321)->Arg(1281);
BENCHMARK(BM_Apply<Method::Bim, true>)->Arg(81)->Arg(321)->Arg(1281);
BENCHMARK(BM_SolveBvp<Method::Bim, true>)->Arg(81)->Arg(321)->Arg(1281);

BENCHMARK_MAIN();
