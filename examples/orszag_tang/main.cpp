// Orszag-Tang vortex (seed 000, §IV-B, Figs. 2 and 3): SPMHD on the periodic unit square with
// five ways of controlling div B: none, artificial resistivity, Euler potentials, constrained
// cleaning, cleaning plus resistivity. Units mu0 = 1, B0 = 1/sqrt(4 pi) (beta0 = 10/3).
// Each variant runs through the shared run driver (run/time_loop.hpp): checkpoints, --restart,
// SIGINT/SIGTERM, last good state on a failure.
#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <sstream>

#include "sphark/cli/options.hpp"
#include "sphark/core/profile.hpp"
#include "sphark/integrate/stepper.hpp"
#include "sphark/io/csv_writer.hpp"
#include "sphark/io/paraview_state.hpp"
#include "sphark/io/visualise.hpp"
#include "sphark/run/restart.hpp"
#include "sphark/run/signals.hpp"
#include "sphark/run/time_loop.hpp"
#include "sphark/schemes/spmhd/spmhd_diagnostics.hpp"
#include "sphark/schemes/spmhd/spmhd_setup.hpp"

using namespace sphark;

namespace {

const std::vector<std::string> kVariants = {"none", "resistivity", "euler", "cleaning", "cleaning+resistivity"};

struct Settings {
  CoreOptions core;
  int nx = 128;
  Real sigma = 0.3, alpha_b = 1.0;
  Real overclean = 8.0;  // cleaning variants: c_h = overclean x max fast speed (docs/spmhd.md)
  Real courant = 0.3;    // every variant: dt = C h / max(v_sig, c_h)
  bool local_ch = false;
  RunControlOptions run;
  std::vector<std::string> argv;
  const Checkpoint* restart = nullptr;
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

std::string scene_text(const Settings& s, const std::string& variant) {
  std::string text;
  append_key_value(text, "variant", variant);
  append_key_value(text, "nx", static_cast<Real>(s.nx));
  append_key_value(text, "sigma", s.sigma);
  append_key_value(text, "alpha_b", s.alpha_b);
  append_key_value(text, "overclean", s.overclean);
  append_key_value(text, "courant", s.courant);
  append_key_value(text, "local_ch", s.local_ch ? 1.0 : 0.0);
  return text;
}

struct RunSummary {
  std::string variant;
  Real mean_at_end = 0, max_at_end = 0, mean_at_half = 0, energy_change = 0, momentum = 0;
  TimeLoopResult loop;
};

// The summary from the run's whole diagnostics table (a restarted run summarises from t = 0).
void summarise(RunSummary& r) {
  const std::string& csv = r.loop.diagnostics;
  const std::vector<Real> t = csv_column(csv, "t"), mean = csv_column(csv, "mean_h_divB_over_B"),
                          mx = csv_column(csv, "max_h_divB_over_B"), e = csv_column(csv, "total_energy"),
                          px = csv_column(csv, "momentum_x"), py = csv_column(csv, "momentum_y");
  if (t.empty()) return;
  r.mean_at_end = mean.back();
  r.max_at_end = mx.back();
  for (std::size_t k = 0; k < t.size(); ++k)
    if (std::abs(t[k] - 0.5) < 1e-9) r.mean_at_half = mean[k];
  r.energy_change = (e.back() - e.front()) / e.front();
  r.momentum = std::hypot(px.back(), py.back());
}

RunSummary run(const std::string& variant, const Settings& s) {
  const CoreOptions& core = s.core;
  const std::filesystem::path dir = core.out / dir_name(variant);
  prepare_output_dir(dir, "orszag_tang");
  const int nx = s.nx, ny = hexagonal_rows(nx);
  const ParticleSet2D p = hexagonal_lattice_unit_box(nx, ny, kOrszagTangRho);
  SpmhdOptions o = variant_options(variant, s);
  o.h_initial = o.eta * std::sqrt(1.0 / (static_cast<Real>(nx) * ny));
  SpmhdScheme<2> scheme(p.m, o, unit_periodic_box());
  std::vector<Real> y(scheme.size(), 0);
  orszag_tang_initial_state(scheme, p, y.data());

  StepperOptions so = stepper_options(core, scheme, "orszag_tang");
  so.cfl_safety = 1.0;
  std::printf("orszag_tang %s: %d x %d = %zu particles, %s\n", variant.c_str(), nx, ny, p.size(), describe(so).c_str());

  TimeLoopSettings ts;
  ts.program = "orszag_tang";
  ts.run = variant;
  ts.argv = s.argv;
  ts.texts = {{"scene", scene_text(s, variant)}};
  ts.t_end = core.t_end;
  ts.sample_every = core.output_every > 0 ? core.output_every : core.t_end;  // 0: first and last only
  ts.diagnostics_csv = dir / "diagnostics.csv";
  ts.columns = {"t", "mean_h_divB_over_B", "max_h_divB_over_B", "kinetic_energy", "magnetic_energy", "thermal_energy",
                "psi_energy", "total_energy", "momentum_x", "momentum_y", "cleaning_speed", "rhs_evals"};
  ts.frames_dir = dir;
  ts.frames_basename = "orszag_tang";
  ts.frame_every = ts.sample_every;
  apply_run_control(ts, s.run, s.restart, dir / "checkpoint.bin");
  ts.progress_interval = 10;

  std::vector<Real> pmag(p.size()), err(p.size()), pos(2 * p.size());
  TimeLoopHooks hooks;
  hooks.diagnostics = [&](Real t, const Real* yy, const StepperStats& st) {
    const SpmhdDiagnostics d = spmhd_diagnostics(scheme, t, yy);
    return std::vector<Real>{t, d.mean_h_divb_over_b, d.max_h_divb_over_b, d.kinetic_energy, d.magnetic_energy,
                             d.thermal_energy, d.psi_energy, d.total_energy, d.momentum[0], d.momentum[1],
                             d.cleaning_speed, static_cast<Real>(st.rhs_evals)};
  };
  hooks.frame = [&](Real, const Real* yy) {  // after diagnostics(): B, div B, h of this state
    const auto& B = scheme.magnetic_field();
    const PeriodicBox<2> box = unit_periodic_box();
    for (std::size_t a = 0; a < p.size(); ++a) {
      const Real b2 = B[3 * a] * B[3 * a] + B[3 * a + 1] * B[3 * a + 1] + B[3 * a + 2] * B[3 * a + 2];
      pmag[a] = 0.5 * b2;
      err[a] = b2 > 0 ? scheme.h()[a] * std::abs(scheme.div_b()[a]) / std::sqrt(b2) : 0.0;
    }
    box.wrap_all(yy, p.size(), pos.data());
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
    f.arrays.push_back({"velocity", yy + scheme.layout().offset(Field::Velocity), 2});
    f.arrays.push_back({"h", scheme.h().data(), 1});
    return f;
  };

  RunSummary r;
  r.variant = variant;
  r.loop = run_time_loop(scheme, scheme.layout(), so, y, ts, hooks);
  write_paraview_state_or_warn(dir / "view.pvsm", {{"orszag_tang.pvd", "div_B"}, {"orszag_tang.pvd", "magnetic_pressure"}});
  summarise(r);
  std::printf("%s: %s\n", variant.c_str(), format_stats(r.loop.stats).c_str());
  return r;
}

void write_summary(const std::vector<RunSummary>& results, int nx, const std::filesystem::path& file) {
  std::ostringstream s;
  s << "variant, nx, mean_h_divB_over_B_t0.5, mean_h_divB_over_B_end, max_h_divB_over_B_end, total_energy_change, "
       "momentum_end, steps, rhs_evals, wall_s\n";
  for (const RunSummary& r : results) {
    char line[512];
    std::snprintf(line, sizeof line, "%s, %d, %.4e, %.4e, %.4e, %.3e, %.3e, %ld, %ld, %.1f%s\n", r.variant.c_str(), nx,
                  r.mean_at_half, r.mean_at_end, r.max_at_end, r.energy_change, r.momentum, r.loop.stats.steps,
                  r.loop.stats.rhs_evals, r.loop.wall_seconds, r.loop.ok() ? "" : " (FAILED)");
    s << line;
  }
  std::cout << s.str();
  write_file_atomically(file, s.str());
}

}  // namespace

int main(int argc, char** argv) {
  const std::optional<Checkpoint> restart = load_restart_option(argc, argv, "orszag_tang");
  const std::vector<std::string> args = run_arguments("orszag_tang", argc, argv, restart ? &*restart : nullptr);
  Settings s;
  CoreOptions& core = s.core;
  core.out = "out/orszag_tang";
  core.t_end = 1;
  core.output_every = 0.05;
  core.stepper = "leapfrog";  // dt = C h / v_sig (max_stable_dt), one RHS per step
  core.rtol = 1e-4;
  core.atol = 1e-6;
  std::string variant = "all";
  OptionParser parser("orszag_tang",
                      "Orszag-Tang vortex (seed 000 §IV-B, Figs. 2-3): div B control by resistivity, Euler potentials "
                      "and constrained hyperbolic/parabolic cleaning");
  std::vector<std::string> steppers = erk_table_names();
  steppers.push_back("ark-imex");
  steppers.push_back("leapfrog");
  add_core_options(parser, core, steppers);
  parser.add("--nx", &s.nx, "particles per row of the hexagonal lattice (rows: nearest even nx*2/sqrt(3)); paper: 512",
             Range{8, 4096});
  std::vector<std::string> allowed = kVariants;
  allowed.push_back("all");
  parser.add("--variant", &variant, "div B control (all: the five in turn)", OneOf{allowed});
  parser.add("--sigma", &s.sigma, "cleaning damping, 1/tau = sigma c_h / h", NonNegative{});
  parser.add("--alpha-b", &s.alpha_b, "artificial resistivity strength of the resistivity variants", Positive{});
  parser.add("--overclean", &s.overclean, "cleaning speed c_h = overclean x max fast speed (cleaning variants)",
             Range{1.0, 100.0});
  parser.add_flag("--local-ch", &s.local_ch,
                  "per-particle c_h = overclean x own fast speed, psi/c_h evolved (Tricco, Price & Bate 2016)");
  parser.add("--courant", &s.courant, "Courant number C of dt = C h / max(v_sig, c_h), every variant",
             Range{0.01, 1.0});
  add_run_options(parser, s.run, "<out>/<variant>/checkpoint.bin");
  const std::vector<const char*> parse_argv = as_argv(args);
  parser.parse_or_exit(static_cast<int>(parse_argv.size()), parse_argv.data());
  check_run_options(parser, s.run, core);
  std::vector<std::string> todo = variant == "all" ? kVariants : std::vector<std::string>{variant};
  if (restart) {  // one variant: the checkpoint's
    const std::string name = restart->text("run");
    if (variant != "all" && variant != name) parser.fail("--variant", variant + " contradicts the checkpoint (variant " + name + ")");
    todo = {name};
    check_restart_text(parser, *restart, "scene", scene_text(s, name), "scene parameters");
    check_restart_t_end(parser, *restart, core.t_end);
  }
  start_run(core, parser.program());
  s.argv.assign(args.begin() + 1, args.end());
  s.restart = restart ? &*restart : nullptr;

  std::vector<RunSummary> results;
  const bool all = todo.size() == kVariants.size();
  const auto summary_file = [&](const std::string& v) {
    return core.out / (all ? "summary.csv" : "summary_" + dir_name(v) + ".csv");
  };
  try {
    for (const std::string& v : todo) {
      results.push_back(run(v, s));
      // a stop signal (checkpoint written) or a failure (last good state written): no further runs
      if (const int code = report_time_loop_end(results.back().loop); code != 0) {
        write_summary(results, s.nx, summary_file(v));
        return code;
      }
    }
  } catch (const std::invalid_argument& e) {
    exit_usage_error(parser.program(), "", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "orszag_tang: %s\n", e.what());
    return 1;
  }
  write_summary(results, s.nx, summary_file(todo[0]));
  if (core.render) run_python("orszag_tang.py", {"--dir", core.out.string()}, false);
  return 0;
}
