// Where the multirate steppers pay (issue #17): work against precision on the oscillator model
// with two separated time scales (sphark/study/oscillator_study.hpp: the case, the five steppers
// and their seven settings). Counters: particle evaluations (the unit of work,
// StepperStats::particle_evals), the error at t = 2, and steps. The time per iteration is the
// run's wall time (each evaluation of a particle costs O(N) here: all pairs; per-step vector work
// weighs more than in SPH, where an evaluation costs microseconds).
//   build/bin/bench_multirate_oscillators --benchmark_counters_tabular=true
//   ... --benchmark_format=csv > wp.csv && /usr/bin/python3 vis/multirate_work_precision.py wp.csv out.png
#include <benchmark/benchmark.h>

#include <exception>

#include "sphark/study/oscillator_study.hpp"

using namespace sphark;

namespace {

void BM_WorkPrecision(benchmark::State& state) {
  const auto method = static_cast<OscillatorMethod>(state.range(0));
  OscillatorStudyRun r;
  for (auto _ : state) {
    try {
      r = run_oscillator_study(method, static_cast<int>(state.range(1)));
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      return;
    }
  }
  state.counters["particle_evals"] = static_cast<double>(r.particle_evals);
  state.counters["error"] = r.error;
  state.counters["steps"] = static_cast<double>(r.steps);
  state.SetLabel(oscillator_method_name(method));
}

}  // namespace

BENCHMARK(BM_WorkPrecision)
    ->ArgsProduct({{0, 1, 2, 3, 4}, {0, 1, 2, 3, 4, 5, 6}})  // OscillatorMethod, setting
    ->ArgNames({"method", "setting"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
