// End-to-end timing of the water drop (examples/water_drop's scene, stepper and tolerances:
// ARKODE_BOGACKI_SHAMPINE_4_2_3, rtol 1e-4, atol 1e-6 times the field scales, advance() per
// output interval 0.002) without output, to measure how much of a step is ARKODE's own vector
// work: the --profile line "stepper" = Advance - Rhs.
//   build/bin/bench_water_drop_timing --t-end 0.02 --threads 1 --profile
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "cpu_time.hpp"
#include "sphark/cli/options.hpp"
#include "sphark/core/profile.hpp"
#include "sphark/integrate/stepper.hpp"
#include "sphark/scenes/water_drop/water_drop.hpp"

using namespace sphark;

using bench::cpu_seconds;

int main(int argc, char** argv) {
  CoreOptions core;
  core.t_end = 0.02;
  core.stepper = "ARKODE_BOGACKI_SHAMPINE_4_2_3";
  core.rtol = 1e-4;
  core.atol = 1e-6;
  core.output_every = 0.002;
  Real spacing = 0.04;
  OptionParser parser("bench_water_drop_timing", "water drop to t_end without output: time split, ARKODE share");
  add_core_options(parser, core);
  parser.add("--spacing", &spacing, "particle spacing (radius 1; 0.04 = the example's 1976 particles)", Positive{});
  parser.parse_or_exit(argc, argv);
  apply_thread_count(core.threads);
  run_profile().enable(core.profile);

  WaterDropConfig cfg;
  cfg.spacing = spacing;
  WaterDrop drop = make_water_drop(cfg);
  OdeSystem& sys = drop.model->system();
  StepperOptions so;  // examples/water_drop/drop_run.cpp: stepper_options()
  so.method = core.stepper;
  so.rtol = core.rtol;
  so.atol = water_drop_absolute_tolerances(drop, core.atol);
  so.fixed_dt = core.dt;
  std::vector<Real> y = drop.y0;
  auto stepper = make_stepper(sys, so, 0.0, y.data());
  std::printf("water drop: %zu particles, %s, %d threads\n", drop.particles(), describe(so).c_str(),
              omp_get_max_threads());
  const double cpu0 = cpu_seconds();
  const auto start = std::chrono::steady_clock::now();
  Real t = 0;
  AdvanceStatus st = AdvanceStatus::Reached;
  for (long k = 1; st == AdvanceStatus::Reached && t < core.t_end * (1 - 1e-12); ++k)
    st = stepper->advance(std::min(core.t_end, k * core.output_every), y.data(), t);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpu = cpu_seconds() - cpu0;
  if (st != AdvanceStatus::Reached) {
    std::cerr << "integration failed: " << stepper->failure_reason() << "\n";
    return 1;
  }
  const StepperStats s = stepper->stats();
  std::printf("t = %g: steps %ld, rhs %ld, wall %.2f s, cpu %.2f s\n", t, s.steps, s.rhs_evals, wall, cpu);
  if (core.profile) {
    const RunProfile& p = run_profile();
    const double adv = p.seconds(Phase::Advance), rhs = p.seconds(Phase::Rhs);
    std::printf("ARKODE share of the steps: (Advance - Rhs) / Advance = %.1f %%\n",
                adv > 0 ? 100 * (adv - rhs) / adv : 0.0);
    p.print(std::cout, wall);
  }
  return 0;
}
