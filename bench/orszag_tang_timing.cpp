// End-to-end timing of the Orszag-Tang scene (seed 000 §IV-B; the same set-up and stepper
// defaults as examples/orszag_tang, advancing per --output-every interval) without writing
// output: wall and CPU time to t_end, steps, RHS calls, the SPMHD pair rate and the final mean
// h|div B|/|B|, then the --profile table.
//   build/bin/bench_orszag_tang_timing --nx 64 --variant cleaning+resistivity --threads 2 --profile
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "cpu_time.hpp"
#include "sphark/cli/options.hpp"
#include "sphark/core/profile.hpp"
#include "sphark/integrate/stepper.hpp"
#include "sphark/diagnostics/spmhd_diagnostics.hpp"
#include "sphark/scenes/orszag_tang/orszag_tang.hpp"

using namespace sphark;

using bench::cpu_seconds;

int main(int argc, char** argv) {
  CoreOptions core;
  core.t_end = 1;
  core.stepper = "leapfrog";  // examples/orszag_tang's default
  core.rtol = 1e-4;
  core.atol = 1e-6;
  core.output_every = 0.05;  // advance() per interval, as the example (bounds ERK steps by the CFL each interval)
  OrszagTangParams params;  // the example's defaults (scenes/orszag_tang)
  params.nx = 64;
  std::string variant = "cleaning+resistivity";
  Real cfl = 1.0;  // examples/orszag_tang: so.cfl_safety = 1
  OptionParser parser("bench_orszag_tang_timing", "Orszag-Tang vortex to t_end without output: time, pair rate, div B");
  std::vector<std::string> steppers = erk_table_names();
  steppers.push_back("leapfrog");
  add_core_options(parser, core, steppers);
  parser.add("--nx", &params.nx, "particles per row of the hexagonal lattice", Range{8, 4096});
  parser.add("--variant", &variant, "div B control", OneOf{orszag_tang_variants()});
  parser.add("--overclean", &params.overclean, "c_h = overclean x max fast speed (cleaning variants)", Range{1.0, 100.0});
  parser.add_flag("--local-ch", &params.local_ch, "per-particle c_h (cleaning variants)");
  parser.add("--cfl", &cfl, "step = cfl x max_stable_dt (leapfrog; cap of the adaptive ERK step)", Positive{});
  parser.add("--skin", &params.skin, "Verlet skin in units of h (results do not depend on it)", Positive{});
  parser.parse_or_exit(argc, argv);
  apply_thread_count(core.threads);
  run_profile().enable(core.profile);

  OrszagTang ot(variant, params);
  SpmhdScheme<2>& scheme = ot.scheme;
  const ParticleSet2D& p = ot.particles;
  const int nx = ot.nx, ny = ot.ny;
  std::vector<Real> y = ot.y0;
  StepperOptions so = stepper_options(core, scheme, "bench_orszag_tang_timing");
  so.cfl_safety = cfl;
  auto stepper = make_stepper(scheme, so, 0.0, y.data());
  std::printf("orszag_tang %s: %d x %d = %zu particles, %s, %d threads\n", variant.c_str(), nx, ny, p.size(),
              describe(so).c_str(), omp_get_max_threads());

  const double cpu0 = cpu_seconds();
  const auto start = std::chrono::steady_clock::now();
  Real t = 0;
  AdvanceStatus st = AdvanceStatus::Reached;
  for (long k = 1; st == AdvanceStatus::Reached && t < core.t_end * (1 - 1e-12); ++k) {
    const Real t_out = core.output_every > 0 ? std::min(core.t_end, k * core.output_every) : core.t_end;
    st = stepper->advance(t_out, y.data(), t);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpu = cpu_seconds() - cpu0;
  if (st != AdvanceStatus::Reached) {
    std::cerr << "integration failed: " << stepper->failure_reason() << "\n";
    return 1;
  }
  const long rhs = scheme.rhs_evaluations();
  const double pairs = scheme.pair_interactions_total() / static_cast<double>(rhs);  // mean per RHS
  const SpmhdDiagnostics d = spmhd_diagnostics(scheme, t, y.data());
  const double n = static_cast<double>(p.size());
  std::printf("t = %g: steps %ld, rhs %ld, neighbour builds %ld, wall %.2f s, cpu %.2f s\n", t, stepper->stats().steps,
              rhs, scheme.neighbour_builds(), wall, cpu);
  std::printf("h solve: %.2f iterations per particle per RHS\n", scheme.h_iterations_total() / (n * rhs));
  const auto hs = std::minmax_element(scheme.h().begin(), scheme.h().end());
  std::printf("listed neighbours per particle at the end %.1f (h from %.4g to %.4g)\n",
              static_cast<double>(scheme.neighbours().list().pairs()) / n, *hs.first, *hs.second);
  std::printf("mean h|div B|/|B| = %.4e, max = %.4e\n", d.mean_h_divb_over_b, d.max_h_divb_over_b);
  std::printf("pairs per particle per RHS %.1f; cpu per particle per RHS %.3f us; pair interactions per cpu-second "
              "%.3e\n",
              pairs / n, 1e6 * cpu / (n * rhs), pairs * rhs / cpu);
  if (core.profile) run_profile().print(std::cout, wall);
  return 0;
}
