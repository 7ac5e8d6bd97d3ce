// Orszag-Tang vortex (seed 000, §IV-B, Figs. 2 and 3): SPMHD on the periodic unit square with
// five ways of controlling div B: none, artificial resistivity, Euler potentials, constrained
// cleaning, cleaning plus resistivity. Units mu0 = 1, B0 = 1/sqrt(4 pi) (beta0 = 10/3).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "sphark/cli/options.hpp"
#include "sphark/integrate/stepper.hpp"
#include "sphark/io/csv_writer.hpp"
#include "sphark/io/progress.hpp"
#include "sphark/io/visualise.hpp"
#include "sphark/io/vtk_series.hpp"
#include "sphark/schemes/spmhd/spmhd_diagnostics.hpp"
#include "sphark/schemes/spmhd/spmhd_setup.hpp"

using namespace sphark;

namespace {

const std::vector<std::string> kVariants = {"none", "resistivity", "euler", "cleaning", "cleaning+resistivity"};

// Settings shared by every variant (the Courant number) and those of the variants that use them.
struct Settings {
  Real sigma = 0.3, alpha_b = 1.0, overclean = 8.0, courant = 0.3;  // overclean: see docs/spmhd.md
  bool local_ch = false;
};

SpmhdOptions variant_options(const std::string& v, const Settings& set) {
  SpmhdOptions o;
  o.gamma = 5.0 / 3.0;
  o.courant = set.courant;
  if (v == "resistivity" || v == "cleaning+resistivity") o.alpha_b = set.alpha_b;
  if (v == "euler") o.field = FieldRepresentation::EulerPotentials;
  if (v == "cleaning" || v == "cleaning+resistivity") {
    o.cleaning = Cleaning::Constrained;
    o.sigma = set.sigma;
    o.overclean = set.overclean;
    o.local_ch = set.local_ch;
  }
  return o;
}

std::string dir_name(const std::string& v) { return v == "cleaning+resistivity" ? "cleaning_resistivity" : v; }

struct RunSummary {
  std::string variant;
  Real mean_at_end = 0, max_at_end = 0, mean_at_half = 0, energy_change = 0, momentum = 0;
  long rhs = 0, steps = 0;
  double wall = 0;
  bool failed = false;
};

RunSummary run(const std::string& variant, const CoreOptions& core, int nx, const Settings& set) {
  const std::filesystem::path dir = core.out / dir_name(variant);
  prepare_output_dir(dir, "orszag_tang");
  const int ny = hexagonal_rows(nx);
  const ParticleSet2D p = hexagonal_lattice_unit_box(nx, ny, kOrszagTangRho);
  SpmhdOptions o = variant_options(variant, set);
  o.h_initial = o.eta * std::sqrt(1.0 / (static_cast<Real>(nx) * ny));
  SpmhdScheme<2> scheme(p.m, o, unit_periodic_box());
  std::vector<Real> y(scheme.size(), 0);
  orszag_tang_initial_state(scheme, p, y.data());

  StepperOptions so = stepper_options(core, scheme, "orszag_tang");
  so.cfl_safety = 1.0;
  auto stepper = make_stepper(scheme, so, 0.0, y.data());

  CsvWriter csv(dir / "diagnostics.csv",
                {"t", "mean_h_divB_over_B", "max_h_divB_over_B", "kinetic_energy", "magnetic_energy", "thermal_energy",
                 "psi_energy", "total_energy", "momentum_x", "momentum_y", "cleaning_speed", "rhs_evals"});
  VtkSeriesWriter series(dir, "orszag_tang");
  std::vector<Real> pmag(p.size()), err(p.size()), pos(2 * p.size());
  std::printf("orszag_tang %s: %d x %d = %zu particles, %s\n", variant.c_str(), nx, ny, p.size(),
              describe(so).c_str());
  RunSummary r;
  r.variant = variant;
  Real t = 0, e0 = 0;
  const Real every = core.output_every > 0 ? core.output_every : core.t_end;  // 0: first and last only
  ProgressReporter progress(0, core.t_end, 10);
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0;; ++k) {
    const SpmhdDiagnostics d = spmhd_diagnostics(scheme, t, y.data());
    if (k == 0) e0 = d.total_energy;
    csv.row({t, d.mean_h_divb_over_b, d.max_h_divb_over_b, d.kinetic_energy, d.magnetic_energy, d.thermal_energy,
             d.psi_energy, d.total_energy, d.momentum[0], d.momentum[1], d.cleaning_speed,
             static_cast<Real>(scheme.rhs_evaluations())});
    r.mean_at_end = d.mean_h_divb_over_b;
    r.max_at_end = d.max_h_divb_over_b;
    if (std::abs(t - 0.5) < 1e-9) r.mean_at_half = d.mean_h_divb_over_b;
    r.energy_change = (d.total_energy - e0) / e0;
    r.momentum = std::hypot(d.momentum[0], d.momentum[1]);
    {
      const auto& B = scheme.magnetic_field();
      const PeriodicBox<2> box = unit_periodic_box();
      for (std::size_t a = 0; a < p.size(); ++a) {
        const Real b2 = B[3 * a] * B[3 * a] + B[3 * a + 1] * B[3 * a + 1] + B[3 * a + 2] * B[3 * a + 2];
        pmag[a] = 0.5 * b2;
        err[a] = b2 > 0 ? scheme.h()[a] * std::abs(scheme.div_b()[a]) / std::sqrt(b2) : 0.0;
        Eigen::Map<Vec<2>>(pos.data() + 2 * a) = box.wrap(Eigen::Map<const Vec<2>>(y.data() + 2 * a));
      }
      ParticleFrame f;
      f.dim = 2;
      f.count = p.size();
      f.positions = pos.data();
      f.arrays.push_back({"density", scheme.rho().data(), 1});
      f.arrays.push_back({"magnetic_pressure", pmag.data(), 1});
      f.arrays.push_back({"div_B", scheme.div_b().data(), 1});
      f.arrays.push_back({"h_divB_over_B", err.data(), 1});
      f.arrays.push_back({"pressure", scheme.pressure().data(), 1});
      f.arrays.push_back({"magnetic_field", B.data(), 3});
      f.arrays.push_back({"velocity", y.data() + scheme.layout().offset(Field::Velocity), 2});
      f.arrays.push_back({"h", scheme.h().data(), 1});
      series.write(f, t);
    }
    if (t >= core.t_end * (1 - 1e-12)) break;
    const Real t_out = std::min(core.t_end, (k + 1) * every);
    if (stepper->advance(t_out, y.data(), t) != AdvanceStatus::Reached) {
      std::cerr << variant << ": integration failed: " << stepper->failure_reason() << "\n";
      r.failed = true;
      break;
    }
    progress.update(t, stepper->stats().steps, stepper->stats().last_dt);
  }
  progress.finish();
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.rhs = scheme.rhs_evaluations();
  r.steps = stepper->stats().steps;
  std::printf("%s: %s\n", variant.c_str(), format_stats(stepper->stats()).c_str());
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CoreOptions core;
  core.t_end = 1;
  core.output_every = 0.05;
  core.stepper = "leapfrog";  // dt = C h / v_sig (max_stable_dt), one RHS per step
  core.rtol = 1e-4;
  core.atol = 1e-6;
  int nx = 128;
  std::string variant = "all";
  Settings set;
  OptionParser parser("orszag_tang",
                      "Orszag-Tang vortex (seed 000 §IV-B, Figs. 2-3): div B control by resistivity, Euler potentials "
                      "and constrained hyperbolic/parabolic cleaning");
  std::vector<std::string> steppers = erk_table_names();
  steppers.push_back("ark-imex");
  steppers.push_back("leapfrog");
  add_core_options(parser, core, steppers);
  parser.add("--nx", &nx, "particles per row of the hexagonal lattice (rows: nearest even nx*2/sqrt(3)); paper: 512",
             Range{8, 4096});
  std::vector<std::string> allowed = kVariants;
  allowed.push_back("all");
  parser.add("--variant", &variant, "div B control (all: the five in turn)", OneOf{allowed});
  parser.add("--sigma", &set.sigma, "cleaning damping, 1/tau = sigma c_h / h", NonNegative{});
  parser.add("--alpha-b", &set.alpha_b, "artificial resistivity strength of the resistivity variants", Positive{});
  parser.add("--overclean", &set.overclean, "cleaning speed c_h = overclean x max fast speed (cleaning variants)",
             Range{1.0, 100.0});
  parser.add_flag("--local-ch", &set.local_ch,
                  "per-particle c_h = overclean x own fast speed, psi/c_h evolved (Tricco, Price & Bate 2016)");
  parser.add("--courant", &set.courant, "Courant number C of dt = C h / max(v_sig, c_h), every variant",
             Range{0.01, 1.0});
  parser.parse_or_exit(argc, argv);
  apply_thread_count(core.threads);
  prepare_output_dir(core.out, parser.program());

  std::vector<std::string> todo = variant == "all" ? kVariants : std::vector<std::string>{variant};
  std::vector<RunSummary> results;
  try {
    for (const std::string& v : todo) results.push_back(run(v, core, nx, set));
  } catch (const std::invalid_argument& e) {
    exit_usage_error(parser.program(), "", e.what());
  }
  std::ostringstream s;
  s << "variant, nx, mean_h_divB_over_B_t0.5, mean_h_divB_over_B_end, max_h_divB_over_B_end, total_energy_change, "
       "momentum_end, steps, rhs_evals, wall_s\n";
  for (const RunSummary& r : results) {
    char line[512];
    std::snprintf(line, sizeof line, "%s, %d, %.4e, %.4e, %.4e, %.3e, %.3e, %ld, %ld, %.1f%s\n", r.variant.c_str(), nx,
                  r.mean_at_half, r.mean_at_end, r.max_at_end, r.energy_change, r.momentum, r.steps, r.rhs, r.wall,
                  r.failed ? " (FAILED)" : "");
    s << line;
  }
  std::cout << s.str();
  write_file_atomically(core.out / (variant == "all" ? "summary.csv" : "summary_" + dir_name(variant) + ".csv"), s.str());
  if (core.render) run_python("orszag_tang.py", {"--dir", core.out.string()}, false);
  for (const RunSummary& r : results)
    if (r.failed) return 1;
  return 0;
}
