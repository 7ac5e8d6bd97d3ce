// Static cleaning test with a free boundary (seed 000, §IV-A, Fig. 1): a disc of 1976 fixed
// particles, only the cleaning subsystem (dB/dt = -grad psi, dpsi/dt = -c_h^2 div B - psi/tau).
// Four runs: {constrained, non-conservative} x {sigma = 0, sigma > 0}.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "sphark/cli/options.hpp"
#include "sphark/integrate/stepper.hpp"
#include "sphark/io/csv_writer.hpp"
#include "sphark/io/visualise.hpp"
#include "sphark/io/vtk_series.hpp"
#include "sphark/schemes/spmhd/spmhd_diagnostics.hpp"
#include "sphark/schemes/spmhd/spmhd_setup.hpp"

using namespace sphark;

namespace {

constexpr Real kBlowUp = 1e4;

struct RunResult {
  std::string name;
  Real initial_max = 0, final_max = 0, peak_max = 0;
  Real growth_rate = 0;  // least-squares slope of ln(max h|div B|/B0), see run()
  Real blew_up_at = -1;  // time at which the cleaning energy exceeded kBlowUp times its start
  Real energy_change = 0;
  long rhs_evals = 0;
  double wall = 0;
  bool failed = false;
};

Real fit_growth_rate(const std::vector<Real>& t, const std::vector<Real>& e, Real t_from) {
  Real n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k] < t_from || !(e[k] > 0)) continue;
    const Real y = std::log(e[k]);
    n += 1, sx += t[k], sy += y, sxx += t[k] * t[k], sxy += t[k] * y;
  }
  return n > 1 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : 0.0;
}

RunResult run(const std::string& name, Cleaning form, Real sigma, const CoreOptions& core, const ParticleSet2D& p,
              bool vtk) {
  SpmhdOptions o;
  o.evolve_particles = false;
  o.cleaning = form;
  o.sigma = sigma;
  // c_h: the fastest wave speed, frozen at t = 0 (no gas pressure in this test: the Alfven
  // speed max |B|/sqrt(rho)), so that the cleaning energy is a constant of the sigma = 0 runs.
  {
    SpmhdScheme<2> probe(p.m, o, std::nullopt, p.x);
    std::vector<Real> y0(probe.size(), 0);
    disc_initial_field(probe, p, y0.data());
    probe.evaluate(0, y0.data());
    o.fixed_ch = probe.cleaning_speed();
  }
  SpmhdScheme<2> scheme(p.m, o, std::nullopt, p.x);
  std::vector<Real> y(scheme.size(), 0);
  disc_initial_field(scheme, p, y.data());

  StepperOptions so = stepper_options(core, scheme, "cleaning_disc");
  auto stepper = make_stepper(scheme, so, 0.0, y.data());

  CsvWriter csv(core.out / (name + ".csv"), {"t", "mean_h_divB_over_B", "max_h_divB_over_B", "magnetic_energy",
                                             "psi_energy", "cleaning_energy", "cleaning_speed",
                                             "max_h_divB_over_B0"});
  std::optional<VtkSeriesWriter> series;
  if (vtk) series.emplace(core.out, name);
  std::vector<Real> ts, maxes;
  RunResult r;
  r.name = name;
  Real e0 = 0, t = 0;
  const Real every = core.output_every > 0 ? core.output_every : core.t_end;  // 0: first and last only
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0;; ++k) {
    const SpmhdDiagnostics d = spmhd_diagnostics(scheme, t, y.data());
    const Real e = d.magnetic_energy + d.psi_energy;
    if (k == 0) e0 = e, r.initial_max = d.max_h_divb_over_b;
    const Real b0 = 1 / std::sqrt(4 * kPi);
    csv.row({t, d.mean_h_divb_over_b, d.max_h_divb_over_b, d.magnetic_energy, d.psi_energy, e, d.cleaning_speed,
             d.max_h_divb / b0});
    ts.push_back(t);
    maxes.push_back(d.max_h_divb / b0);
    r.final_max = d.max_h_divb_over_b;
    r.peak_max = std::max(r.peak_max, d.max_h_divb_over_b);
    r.energy_change = (e - e0) / e0;
    if (series && (k % 20 == 0 || t >= core.t_end)) {
      ParticleFrame f;
      f.dim = 2;
      f.count = p.size();
      f.positions = p.x.data();
      f.arrays.push_back({"magnetic_field", scheme.magnetic_field().data(), 3});
      f.arrays.push_back({"psi", y.data() + scheme.layout().offset(Field::Psi), 1});
      f.arrays.push_back({"div_B", scheme.div_b().data(), 1});
      f.arrays.push_back({"density", scheme.rho().data(), 1});
      series->write(f, t);
    }
    if (t >= core.t_end * (1 - 1e-12)) break;
    if (e > kBlowUp * e0) {  // the non-conservative form grows exponentially: stop, report
      r.blew_up_at = t;
      break;
    }
    const Real t_out = std::min(core.t_end, (k + 1) * every);
    if (stepper->advance(t_out, y.data(), t) != AdvanceStatus::Reached) {
      std::cerr << name << ": integration failed: " << stepper->failure_reason() << "\n";
      r.failed = true;
      break;
    }
  }
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.rhs_evals = scheme.rhs_evaluations();
  // Growth rate of max h|div B|/B0: over the last unit of time before a blow-up, else over the
  // second half of the run.
  r.growth_rate = r.blew_up_at > 0 ? fit_growth_rate(ts, maxes, r.blew_up_at - 1) : fit_growth_rate(ts, maxes, 0.5 * core.t_end);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CoreOptions core;
  core.t_end = 10;
  core.output_every = 0.05;
  core.rtol = 1e-7;
  core.atol = 1e-10;
  core.stepper = "ARKODE_DORMAND_PRINCE_7_4_5";
  Real sigma = 0.3;
  OptionParser parser("cleaning_disc",
                      "Free-boundary disc, cleaning subsystem only (seed 000 §IV-A, Fig. 1): constrained vs "
                      "non-conservative cleaning, sigma = 0 and sigma > 0");
  std::vector<std::string> steppers = erk_table_names();
  steppers.push_back("ark-imex");
  add_core_options(parser, core, steppers);
  parser.add("--sigma", &sigma, "damping strength of the sigma > 0 runs (1/tau = sigma c_h / h)", Positive{});
  parser.parse_or_exit(argc, argv);
  apply_thread_count(core.threads);
  prepare_output_dir(core.out, parser.program());

  const ParticleSet2D p = disc_square_lattice(1.0, 0.04, 1.0);
  std::printf("cleaning_disc: %zu particles, t_end = %g, sigma = %g\n", p.size(), core.t_end, sigma);
  std::vector<RunResult> results;
  try {
    results.push_back(run("constrained_sigma0", Cleaning::Constrained, 0, core, p, true));
    results.push_back(run("constrained_damped", Cleaning::Constrained, sigma, core, p, false));
    results.push_back(run("nonconservative_sigma0", Cleaning::NonConservative, 0, core, p, true));
    results.push_back(run("nonconservative_damped", Cleaning::NonConservative, sigma, core, p, false));
  } catch (const std::invalid_argument& e) {
    exit_usage_error(parser.program(), "", e.what());
  }
  std::ostringstream summary;
  summary << "run, initial_max_h_divB_over_B, peak, final, growth_rate_of_max_h_divB, cleaning_energy_change, "
             "blew_up_at, rhs_evals, wall_s\n";
  for (const RunResult& r : results) {
    char line[512];
    std::snprintf(line, sizeof line, "%s, %.4e, %.4e, %.4e, %.4f, %.3e, %.3f, %ld, %.2f%s\n", r.name.c_str(),
                  r.initial_max, r.peak_max, r.final_max, r.growth_rate, r.energy_change, r.blew_up_at, r.rhs_evals,
                  r.wall,
                  r.failed ? " (FAILED)" : "");
    summary << line;
  }
  std::cout << summary.str();
  write_file_atomically(core.out / "summary.csv", summary.str());
  if (core.render) {
    run_python("cleaning_disc.py", {"--dir", core.out.string(), "--out", (core.out / "fig1_max_divB.png").string()},
               false);
  }
  for (const RunResult& r : results)
    if (r.failed) return 1;
  return 0;
}
