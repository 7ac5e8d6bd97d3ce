// SPMHD right-hand side (constrained cleaning + artificial resistivity, seed 000 §II) on the
// Orszag-Tang state (2D hexagonal lattice, N = 10^3 .. 10^6) and on a 3D cubic lattice (27,000,
// 97,336 and 10^6 particles, to set beside bench_gravity at the same N): ns per
// particle per RHS call and pair interactions (|x_ab| < 2 max(h_a, h_b)) per second.
//
// Each timed call sees new positions (the state alternates between y and y + dt v with
// dt = 0.05 h, a typical leapfrog step), as in a run: the h solve runs every call, from the
// previous h (about 3 Newton steps, as in the Orszag-Tang run), on Verlet lists
// that stay valid (rebuilds are timed by bench_neighbours). The shuffled row starts from the
// particles in random order: the scheme's cell-ordered slots make it cost the same. Single-thread rows report CPU time;
// the 2-thread rows report wall time (UseRealTime), for the thread-scaling figure.
//   build/bin/bench_spmhd_rhs --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "sphark/scenes/orszag_tang/orszag_tang.hpp"

using namespace sphark;

namespace {

SpmhdOptions options() {
  SpmhdOptions o;  // examples/orszag_tang, variant cleaning+resistivity
  o.cleaning = Cleaning::Constrained;
  o.alpha_b = 1.0;
  return o;
}

// Times rhs() alternating between y and y + dt v; reports the counters.
template <int D>
void time_rhs(benchmark::State& state, SpmhdScheme<D>& scheme, std::vector<Real>& y, Real h) {
  std::vector<Real> y1 = y, ydot(y.size());
  const std::size_t n = scheme.particles(), xo = scheme.position_offset(), vo = scheme.velocity_offset();
  for (std::size_t k = 0; k < D * n; ++k) y1[xo + k] += 0.05 * h * y[vo + k];
  scheme.rhs(0, y.data(), ydot.data());  // lists, h from the first guess
  long calls = 0;
  for (auto _ : state) {
    scheme.rhs(0, (calls++ % 2 ? y : y1).data(), ydot.data());
    benchmark::DoNotOptimize(ydot.data());
  }
  const auto nd = static_cast<double>(n);
  const auto pairs = static_cast<double>(scheme.interacting_pairs());
  state.counters["ns_per_particle"] =
      benchmark::Counter(nd * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["pairs_per_s"] = benchmark::Counter(pairs, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["pairs_per_particle"] = pairs / nd;
  state.counters["particles"] = nd;
  state.counters["threads"] = omp_get_max_threads();
  state.counters["h_iterations"] = scheme.h_iterations_total() / (nd * static_cast<double>(scheme.rhs_evaluations()));
}

void BM_SpmhdRhs2D(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  const int nx = static_cast<int>(std::lround(std::sqrt(state.range(0) * std::sqrt(3.0) / 2)));
  const int ny = hexagonal_rows(nx);
  ParticleSet2D p = hexagonal_lattice_unit_box(nx, ny, kOrszagTangRho);
  if (state.range(2) != 0) {  // particles in random order (as after a flow has mixed them)
    std::vector<std::size_t> perm(p.size());
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), std::mt19937_64(3));
    ParticleSet2D q = p;
    for (std::size_t i = 0; i < perm.size(); ++i) {
      q.x[2 * i] = p.x[2 * perm[i]];
      q.x[2 * i + 1] = p.x[2 * perm[i] + 1];
      q.m[i] = p.m[perm[i]];
    }
    p = q;
  }
  SpmhdOptions o = options();
  o.h_initial = o.eta * std::sqrt(1.0 / (static_cast<Real>(nx) * ny));
  SpmhdScheme<2> scheme(p.m, o, unit_periodic_box());
  std::vector<Real> y(scheme.size(), 0);
  orszag_tang_initial_state(scheme, p, y.data());
  time_rhs<2>(state, scheme, y, o.h_initial);
  state.counters["shuffled"] = static_cast<double>(state.range(2));
}

// 3D: cubic lattice in the periodic unit cube, the Orszag-Tang fields in the x-y plane plus a
// z-dependence, rho = 1, P = 1 (u = 1.5).
void BM_SpmhdRhs3D(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  const int nx = static_cast<int>(std::lround(std::cbrt(static_cast<double>(state.range(0)))));
  const std::size_t n = static_cast<std::size_t>(nx) * nx * nx;
  const Real dx = 1.0 / nx;
  PeriodicBox<3> box;
  box.periodic = {true, true, true};
  SpmhdOptions o = options();
  o.h_initial = o.eta * dx;
  SpmhdScheme<3> scheme(std::vector<Real>(n, dx * dx * dx), o, box);
  std::vector<Real> y(scheme.size(), 0);
  const StateLayout& L = scheme.layout();
  auto x = vector_field<3>(y.data(), L, Field::Position);
  auto v = vector_field<3>(y.data(), L, Field::Velocity);
  auto B = vector_field<3>(y.data(), L, Field::MagneticField);
  auto u = scalar_field(y.data(), L, Field::InternalEnergy);
  const Real tp = 2 * kPi, b0 = 1 / std::sqrt(4 * kPi);
  for (std::size_t a = 0; a < n; ++a) {
    const Real px = (a % nx + 0.5) * dx, py = (a / nx % nx + 0.5) * dx, pz = (a / nx / nx + 0.5) * dx;
    x.col(a) = Vec<3>(px, py, pz);
    v.col(a) = Vec<3>(-std::sin(tp * py), std::sin(tp * px), 0.1 * std::sin(tp * pz));
    B.col(a) = b0 * Vec<3>(-std::sin(tp * py), std::sin(2 * tp * px), 0.1 * std::cos(tp * pz));
    u(a) = 1.5;
  }
  time_rhs<3>(state, scheme, y, o.h_initial);
}

}  // namespace

BENCHMARK(BM_SpmhdRhs2D)->ArgNames({"n", "threads", "shuffled"})->Args({1000, 1, 0})->Args({10000, 1, 0})
    ->Args({100000, 1, 0})->Args({100000, 1, 1})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SpmhdRhs2D)->ArgNames({"n", "threads", "shuffled"})->Args({1000000, 1, 0})->Iterations(4)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SpmhdRhs2D)->ArgNames({"n", "threads", "shuffled"})->Args({100000, 2, 0})->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SpmhdRhs2D)->ArgNames({"n", "threads", "shuffled"})->Args({1000000, 2, 0})->Iterations(4)->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SpmhdRhs3D)->ArgNames({"n", "threads"})->Args({27000, 1})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SpmhdRhs3D)->ArgNames({"n", "threads"})->Args({97336, 1})->Args({1000000, 1})->Iterations(3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SpmhdRhs3D)->ArgNames({"n", "threads"})->Args({27000, 2})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
