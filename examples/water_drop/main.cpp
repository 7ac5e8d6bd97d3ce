// The oscillating elliptic water drop of seed 000, §IV-D: weakly compressible SPH with and
// without constrained velocity divergence cleaning, against the exact incompressible ellipse.
// See README.md in this folder for what it reproduces, the options and run times.
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>

#include "drop_charts.hpp"
#include "drop_run.hpp"
#include "sphark/cli/options.hpp"
#include "sphark/cli/run_record.hpp"
#include "sphark/io/paraview_state.hpp"
#include "sphark/integrate/stepper.hpp"
#include "sphark/run/restart.hpp"
#include "sphark/core/profile.hpp"
#include "sphark/run/signals.hpp"

using namespace sphark;

namespace {
void print_summary(const std::string& label, const DropRunSummary& s) {
  std::printf("%-9s %s t=%.4g  particles %zu  wall %.1f s  %s\n", label.c_str(), s.loop.ok() ? "ok    " : "FAILED",
              s.loop.t_reached, s.particles, s.loop.wall_seconds, format_stats(s.loop.stats).c_str());
  std::printf("          max semi-axis error %.2f%% (t=%.4f), at first squeeze %.2f%%, <mean|div v|>_t %.4g,"
              " max density error %.3g%%, KE(end) %.6g, energy drift %.3g%%, neighbour builds %ld\n",
              100 * s.max_semi_axis_error, s.time_of_max_error, 100 * s.squeeze_error, s.mean_abs_div_v_time_avg,
              100 * s.max_rel_density_error, s.kinetic_energy_end, 100 * s.total_energy_drift, s.neighbour_builds);
  if (!s.loop.ok()) std::printf("          reason: %s\n", s.loop.failure.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  const std::optional<Checkpoint> restart = load_restart_option(argc, argv, "water_drop");
  // Options of this run (stored in its checkpoints): a restart's stored ones, then these.
  const std::vector<std::string> args = run_arguments("water_drop", argc, argv, restart ? &*restart : nullptr);
  DropRunSettings base;
  base.core.out = "out/water_drop";
  base.core.t_end = 0.1;
  base.core.stepper = "ARKODE_BOGACKI_SHAMPINE_4_2_3";
  base.core.rtol = 1e-4;
  base.core.atol = 1e-6;
  base.core.output_every = 0.002;
  WaterDropConfig& sc = base.scene;
  std::string cleaning = "both";
  std::string initial_pressure = "exact";

  OptionParser p("water_drop", "oscillating elliptic water drop (seed 000 §IV-D): WCSPH with/without velocity cleaning");
  add_core_options(p, base.core);
  p.add("--cleaning", &cleaning, "constrained velocity cleaning: on, off, or both (cleaned + control runs)",
        OneOf{{"on", "off", "both"}});
  p.add("--amplitude", &sc.amplitude, "A of the initial velocity v = (-A x, A y)", NonNegative{});
  p.add("--omega", &sc.omega, "omega of the radial body force -omega^2 r", NonNegative{});
  p.add("--radius", &sc.radius, "drop radius R", Positive{});
  p.add("--spacing", &sc.spacing, "square-lattice spacing (0.04: 1976 particles for R = 1)", Positive{});
  p.add("--sound-speed", &sc.sound_speed, "c_s of the Tait EOS (26)", Positive{});
  p.add("--rho0", &sc.rho0, "reference density", Positive{});
  p.add("--kernel", &sc.kernel, "smoothing kernel", OneOf{wcsph_kernel_names()});
  p.add("--h-factor", &sc.h_factor, "h / spacing (eq. (5) with eta = h-factor)", Range{0.8, 4.0});
  p.add("--alpha", &sc.alpha, "Monaghan artificial viscosity coefficient", NonNegative{});
  p.add("--delta", &sc.delta, "delta-SPH density diffusion coefficient (0: off)", NonNegative{});
  p.add_switch("--diffusion-correction", &sc.diffusion_correction,
               "Antuono et al. (2010) correction of the density diffusion (off: Molteni & Colagrossi)");
  p.add("--sigma", &sc.clean_sigma, "cleaning damping sigma, tau = h / (sigma c_h)", NonNegative{});
  p.add("--cfl", &sc.cfl, "CFL number of the stability limit (leapfrog step, adaptive step cap)", Positive{});
  p.add("--initial-pressure", &initial_pressure, "initial density from the exact pressure, or rho0 everywhere",
        OneOf{{"exact", "zero"}});
  p.add("--diagnostics-every", &base.diagnostics_every, "time between diagnostics rows", Positive{});
  RunControlOptions run_control;
  add_run_options(p, run_control, "<out>/<run>/checkpoint.bin");
  const std::vector<const char*> parse_argv = as_argv(args);
  p.parse_or_exit(static_cast<int>(parse_argv.size()), parse_argv.data());
  sc.exact_initial_pressure = initial_pressure == "exact";
  if (sc.spacing > 0.5 * sc.radius) p.fail("--spacing", "must be at most half the radius");
  check_run_options(p, run_control, base.core);
  limit_to_t_end(p, "--diagnostics-every", base.diagnostics_every, base.core.t_end);
  base.checkpoint_every = run_control.checkpoint_every;
  base.inject_nan_at = run_control.inject_nan_at;
  std::vector<std::pair<std::string, bool>> runs;
  if (cleaning != "off") runs.push_back({"cleaned", true});
  if (cleaning != "on") runs.push_back({"control", false});
  if (restart) {  // one run: the checkpoint's
    const std::string label = restart->text("run");
    if (cleaning != "both" && (cleaning == "on") != (label == "cleaned"))
      p.fail("--cleaning", cleaning + " contradicts the checkpoint (a " + label + " run)");
    runs = {{label, label == "cleaned"}};
    WaterDropConfig c = sc;
    c.cleaning = label == "cleaned";
    check_restart_text(p, *restart, "scene", scene_text(c), "scene parameters");
    check_restart_t_end(p, *restart, base.core.t_end);
  }
  start_run(base.core, p.program());
  RunRecord record = start_run_record(p, base.core.out);  // run.json: options, version, start
  base.argv.assign(args.begin() + 1, args.end());
  base.restart = restart ? &*restart : nullptr;
  std::vector<std::pair<std::string, DropRunSummary>> results;
  for (const auto& [label, on] : runs) {
    DropRunSettings s = base;
    s.label = label;
    s.scene.cleaning = on;
    s.core.out = base.core.out / label;
    prepare_output_dir(s.core.out, p.program());
    std::fprintf(stderr, "water_drop: %s run -> %s\n", label.c_str(), s.core.out.c_str());
    try {
      results.push_back({label, run_water_drop(s)});
    } catch (const std::exception& e) {
      std::fprintf(stderr, "water_drop: %s run: %s\n", label.c_str(), e.what());
      return record.finish_with_exit_code(1, label + " run: " + e.what());
    }
    const DropRunSummary& r = results.back().second;
    // a stop signal (checkpoint written) or a failure (last good state written): no further runs
    if (const int code = report_time_loop_end(r.loop); code != 0) {
      if (!r.loop.ok()) print_summary(label, r);
      return record.finish_with_exit_code(code, r.loop.failure);
    }
  }
  std::printf("\nwater drop, %s, rtol %g, atol %g, dt %g, t_end %g\n", base.core.stepper.c_str(), base.core.rtol,
              base.core.atol, base.core.dt, base.core.t_end);
  for (const auto& [label, s] : results) print_summary(label, s);
  write_drop_summary(base.core.out, results);
  if (base.core.render) {
    const Real every = base.core.output_every > 0 ? base.core.output_every : base.core.t_end;
    make_drop_pictures(base.core.out, results, every, base.core.t_end);
  }
  std::printf("\noutputs in %s/{%s}: diagnostics.csv, drop.pvd (+ drop_*.vtp), summary.csv, *.png\n"
              "open in ParaView: paraview %s/%s/drop.pvd  (colour by density, pressure, div_v, psi)\n",
              base.core.out.c_str(), results.size() > 1 ? "cleaned,control" : results[0].first.c_str(),
              base.core.out.c_str(), results[0].first.c_str());
  std::vector<ParaViewView> views;  // cleaned | control side by side, coloured by pressure
  for (const auto& r : results) views.push_back({std::filesystem::path(r.first) / "drop.pvd", "pressure"});
  write_paraview_state_or_warn(base.core.out / "view.pvsm", views);
  for (const auto& r : results)
    if (!r.second.loop.ok()) return record.finish_with_exit_code(3, r.first + " run: " + r.second.loop.failure);
  return record.finish_with_exit_code(0);
}
