// Static cleaning test with a free boundary (seed 000, §IV-A, Fig. 1): a disc of 1976 fixed
// particles, only the cleaning subsystem (dB/dt = -grad psi, dpsi/dt = -c_h^2 div B - psi/tau).
// Four runs: {constrained, non-conservative} x {sigma = 0, sigma > 0}, each through the shared
// run driver (run/time_loop.hpp): checkpoints, --restart, SIGINT/SIGTERM, last good state.
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

constexpr Real kBlowUp = 1e4;

struct Variant {
  std::string name;
  Cleaning form;
  bool damped;
  bool vtk;
};
const std::vector<Variant> kVariants = {{"constrained_sigma0", Cleaning::Constrained, false, true},
                                        {"constrained_damped", Cleaning::Constrained, true, false},
                                        {"nonconservative_sigma0", Cleaning::NonConservative, false, true},
                                        {"nonconservative_damped", Cleaning::NonConservative, true, false}};

struct Settings {
  CoreOptions core;
  Real sigma = 0.3, spacing = 0.04;
  RunControlOptions run;
  std::vector<std::string> argv;
  const Checkpoint* restart = nullptr;
};

struct RunResult {
  std::string name;
  Real initial_max = 0, final_max = 0, peak_max = 0;
  Real growth_rate = 0;  // least-squares slope of ln(max h|div B|/B0), see summarise()
  Real blew_up_at = -1;  // time at which the cleaning energy exceeded kBlowUp times its start
  Real energy_change = 0;
  TimeLoopResult loop;
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

std::string scene_text(const Settings& s, const Variant& v) {
  std::string text;
  append_key_value(text, "variant", v.name);
  append_key_value(text, "spacing", s.spacing);
  append_key_value(text, "sigma", v.damped ? s.sigma : 0.0);
  return text;
}

// The summary of a run from its whole diagnostics table (so a restarted run summarises the
// whole run from t = 0).
void summarise(RunResult& r, Real t_end) {
  const std::string& csv = r.loop.diagnostics;
  const std::vector<Real> t = csv_column(csv, "t"), mx = csv_column(csv, "max_h_divB_over_B"),
                          mx0 = csv_column(csv, "max_h_divB_over_B0"), e = csv_column(csv, "cleaning_energy");
  if (t.empty()) return;
  r.initial_max = mx.front();
  r.final_max = mx.back();
  for (Real v : mx) r.peak_max = std::max(r.peak_max, v);
  r.energy_change = (e.back() - e.front()) / e.front();
  if (r.loop.status == TimeLoopStatus::EndedEarly) r.blew_up_at = t.back();
  // Growth rate of max h|div B|/B0: over the last unit of time before a blow-up, else over the
  // second half of the run.
  r.growth_rate = fit_growth_rate(t, mx0, r.blew_up_at > 0 ? r.blew_up_at - 1 : 0.5 * t_end);
}

RunResult run(const Variant& v, const Settings& s, const ParticleSet2D& p) {
  const CoreOptions& core = s.core;
  SpmhdOptions o;
  o.evolve_particles = false;
  o.cleaning = v.form;
  o.sigma = v.damped ? s.sigma : 0;
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

  TimeLoopSettings ts;
  ts.program = "cleaning_disc";
  ts.run = v.name;
  ts.argv = s.argv;
  ts.texts = {{"scene", scene_text(s, v)}};
  ts.t_end = core.t_end;
  ts.sample_every = core.output_every > 0 ? core.output_every : core.t_end;  // 0: first and last only
  ts.diagnostics_csv = core.out / (v.name + ".csv");
  ts.columns = {"t", "mean_h_divB_over_B", "max_h_divB_over_B", "magnetic_energy", "psi_energy", "cleaning_energy",
                "cleaning_speed", "max_h_divB_over_B0"};
  if (v.vtk) {
    ts.frames_dir = core.out;
    ts.frames_basename = v.name;
    ts.frame_every = 20 * ts.sample_every;
  }
  apply_run_control(ts, s.run, s.restart, core.out / (v.name + ".checkpoint.bin"));
  ts.progress_interval = 10;

  Real e0 = 0, e_last = 0;
  TimeLoopHooks hooks;
  hooks.state = {{"e0", &e0}, {"e_last", &e_last}};
  hooks.diagnostics = [&](Real t, const Real* yy, const StepperStats&) {
    const SpmhdDiagnostics d = spmhd_diagnostics(scheme, t, yy);
    e_last = d.magnetic_energy + d.psi_energy;
    if (t == 0) e0 = e_last;
    const Real b0 = 1 / std::sqrt(4 * kPi);
    return std::vector<Real>{t, d.mean_h_divb_over_b, d.max_h_divb_over_b, d.magnetic_energy, d.psi_energy, e_last,
                             d.cleaning_speed, d.max_h_divb / b0};
  };
  hooks.frame = [&](Real, const Real* yy) {
    ParticleFrame f;
    f.dim = 2;
    f.count = p.size();
    f.positions = p.x.data();
    f.arrays.push_back({"magnetic_field", scheme.magnetic_field().data(), 3});
    f.arrays.push_back({"psi", yy + scheme.layout().offset(Field::Psi), 1});
    f.arrays.push_back({"div_B", scheme.div_b().data(), 1});
    f.arrays.push_back({"density", scheme.rho().data(), 1});
    return f;
  };
  // the non-conservative form grows exponentially: stop, report
  hooks.finished = [&](Real) { return e_last > kBlowUp * e0; };

  RunResult r;
  r.name = v.name;
  const StepperOptions so = stepper_options(core, scheme, "cleaning_disc");
  r.loop = run_time_loop(scheme, scheme.layout(), so, y, ts, hooks);
  if (v.vtk) write_paraview_state_or_warn(core.out / ("view_" + v.name + ".pvsm"), {{v.name + ".pvd", "div_B"}});
  summarise(r, core.t_end);
  return r;
}

void write_summary(const std::vector<RunResult>& results, const std::filesystem::path& file) {
  std::ostringstream summary;
  summary << "run, initial_max_h_divB_over_B, peak, final, growth_rate_of_max_h_divB, cleaning_energy_change, "
             "blew_up_at, rhs_evals, wall_s\n";
  for (const RunResult& r : results) {
    char line[512];
    std::snprintf(line, sizeof line, "%s, %.4e, %.4e, %.4e, %.4f, %.3e, %.3f, %ld, %.2f%s\n", r.name.c_str(),
                  r.initial_max, r.peak_max, r.final_max, r.growth_rate, r.energy_change, r.blew_up_at,
                  r.loop.stats.rhs_evals, r.loop.wall_seconds, r.loop.ok() ? "" : " (FAILED)");
    summary << line;
  }
  std::cout << summary.str();
  write_file_atomically(file, summary.str());
}

}  // namespace

int main(int argc, char** argv) {
  const std::optional<Checkpoint> restart = load_restart_option(argc, argv, "cleaning_disc");
  const std::vector<std::string> args = run_arguments("cleaning_disc", argc, argv, restart ? &*restart : nullptr);
  Settings s;
  CoreOptions& core = s.core;
  core.out = "out/cleaning_disc";
  core.t_end = 10;
  core.output_every = 0.05;
  core.rtol = 1e-7;
  core.atol = 1e-10;
  core.stepper = "ARKODE_DORMAND_PRINCE_7_4_5";
  std::string variant = "all";
  OptionParser parser("cleaning_disc",
                      "Free-boundary disc, cleaning subsystem only (seed 000 §IV-A, Fig. 1): constrained vs "
                      "non-conservative cleaning, sigma = 0 and sigma > 0");
  std::vector<std::string> steppers = erk_table_names();
  steppers.push_back("ark-imex");
  add_core_options(parser, core, steppers);
  parser.add("--sigma", &s.sigma, "damping strength of the sigma > 0 runs (1/tau = sigma c_h / h)", Positive{});
  parser.add("--spacing", &s.spacing, "lattice spacing of the unit disc (seed: 0.04, 1976 particles)", Positive{});
  std::vector<std::string> names{"all"};
  for (const Variant& v : kVariants) names.push_back(v.name);
  parser.add("--variant", &variant, "which run (all: the four in turn)", OneOf{names});
  add_run_options(parser, s.run, "<out>/<run>.checkpoint.bin");
  const std::vector<const char*> parse_argv = as_argv(args);
  parser.parse_or_exit(static_cast<int>(parse_argv.size()), parse_argv.data());
  if (s.spacing > 0.25) parser.fail("--spacing", "must be at most 0.25 (a quarter of the disc radius)");
  check_run_options(parser, s.run, core);
  std::vector<Variant> todo;
  for (const Variant& v : kVariants)
    if (variant == "all" || variant == v.name) todo.push_back(v);
  if (restart) {  // one run: the checkpoint's
    const std::string name = restart->text("run");
    if (variant != "all" && variant != name) parser.fail("--variant", variant + " contradicts the checkpoint (run " + name + ")");
    todo.clear();
    for (const Variant& v : kVariants)
      if (v.name == name) todo.push_back(v);
    if (todo.empty()) parser.fail("--restart", "unknown run '" + name + "' in the checkpoint");
    check_restart_text(parser, *restart, "scene", scene_text(s, todo[0]), "scene parameters");
    check_restart_t_end(parser, *restart, core.t_end);
  }
  start_run(core, parser.program());
  s.argv.assign(args.begin() + 1, args.end());
  s.restart = restart ? &*restart : nullptr;

  const ParticleSet2D p = disc_square_lattice(1.0, s.spacing, 1.0);
  std::printf("cleaning_disc: %zu particles, t_end = %g, sigma = %g\n", p.size(), core.t_end, s.sigma);
  std::vector<RunResult> results;
  try {
    for (const Variant& v : todo) {
      results.push_back(run(v, s, p));
      // a stop signal (checkpoint written) or a failure (last good state written): no further runs
      if (const int code = report_time_loop_end(results.back().loop); code != 0) {
        write_summary(results, core.out / ("summary_" + v.name + ".csv"));
        return code;
      }
    }
  } catch (const std::invalid_argument& e) {
    exit_usage_error(parser.program(), "", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cleaning_disc: %s\n", e.what());
    return 1;
  }
  const bool all = todo.size() == kVariants.size();
  write_summary(results, core.out / (all ? "summary.csv" : "summary_" + todo[0].name + ".csv"));
  if (core.render && all) {
    run_python("cleaning_disc.py", {"--dir", core.out.string(), "--out", (core.out / "fig1_max_divB.png").string()},
               false);
  }
  return 0;
}
