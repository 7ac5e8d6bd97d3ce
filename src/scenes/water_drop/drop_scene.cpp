#include "sphark/scenes/water_drop/drop_scene.hpp"

#include <cmath>
#include <cstdio>

#include "drop_run.hpp"

namespace sphark {

WaterDropScene::WaterDropScene() = default;
WaterDropScene::~WaterDropScene() = default;

std::string WaterDropScene::description() const {
  return "oscillating elliptic water drop (seed 000 §IV-D): WCSPH with/without velocity cleaning";
}

void WaterDropScene::set_defaults(CoreOptions& core) {
  core.out = "out/water_drop";
  core.t_end = 0.1;
  core.stepper = "ARKODE_BOGACKI_SHAMPINE_4_2_3";
  core.rtol = 1e-4;
  core.atol = 1e-6;
  core.output_every = 0.002;
}

void WaterDropScene::add_options(OptionParser& p) {
  WaterDropConfig& sc = config_;
  p.add("--cleaning", &cleaning_, "constrained velocity cleaning: on, off, or both (cleaned + control runs)",
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
  p.add("--initial-pressure", &initial_pressure_, "initial density from the exact pressure, or rho0 everywhere",
        OneOf{{"exact", "zero"}});
  p.add("--diagnostics-every", &diagnostics_every_, "time between diagnostics rows", Positive{});
}

void WaterDropScene::check_options(const OptionParser& p, CoreOptions& core, const RunControlOptions&, bool) {
  config_.exact_initial_pressure = initial_pressure_ == "exact";
  if (config_.spacing > 0.5 * config_.radius) p.fail("--spacing", "must be at most half the radius");
  limit_to_t_end(p, "--diagnostics-every", diagnostics_every_, core.t_end);
}

std::vector<std::string> WaterDropScene::run_names() const {
  std::vector<std::string> runs;
  if (cleaning_ != "off") runs.push_back("cleaned");
  if (cleaning_ != "on") runs.push_back("control");
  return runs;
}

void WaterDropScene::check_restart_run(const OptionParser& p, const std::string& run) const {
  if (cleaning_ != "both" && (cleaning_ == "on") != (run == "cleaned"))
    p.fail("--cleaning", cleaning_ + " contradicts the checkpoint (a " + run + " run)");
}

WaterDropConfig WaterDropScene::config_of(const std::string& run) const {
  WaterDropConfig c = config_;
  c.cleaning = run == "cleaned";
  return c;
}

std::string WaterDropScene::scene_text(const std::string& run) const { return sphark::scene_text(config_of(run)); }

std::unique_ptr<SceneRun> WaterDropScene::make_run(const std::string& run, const CoreOptions& core) {
  return std::make_unique<DropRun>(config_of(run), diagnostics_every_, core.output_every);
}

// The square lattice inside the disc: pi R^2 / dx^2 points (1976 for R = 1, dx = 0.04).
Real WaterDropScene::predicted_particles(const std::string&) const {
  return kPi * config_.radius * config_.radius / (config_.spacing * config_.spacing);
}

std::unique_ptr<SceneRun> WaterDropScene::make_probe_run(const std::string& run, const CoreOptions& core,
                                                         Real particles) {
  WaterDropConfig c = config_of(run);
  if (predicted_particles(run) > particles) c.spacing = c.radius * std::sqrt(kPi / particles);
  return std::make_unique<DropRun>(c, diagnostics_every_, core.output_every);
}

void WaterDropScene::finished(const std::string& run, SceneRun& r, const TimeLoopResult& result) {
  results_.emplace_back(run, static_cast<DropRun&>(r).summary(result));
}

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

int WaterDropScene::report(const CoreOptions& core, const std::vector<std::string>&, bool all_ok) {
  if (results_.empty()) return 0;
  if (!all_ok) {  // the failed or stopped run's summary only
    if (!results_.back().second.loop.ok()) print_summary(results_.back().first, results_.back().second);
    return 0;
  }
  std::printf("\nwater drop, %s, rtol %g, atol %g, dt %g, t_end %g\n", core.stepper.c_str(), core.rtol, core.atol,
              core.dt, core.t_end);
  for (const auto& [label, s] : results_) print_summary(label, s);
  write_drop_summary(core.out, results_);
  if (core.render) make_drop_pictures(core.out, results_, core.output_every > 0 ? core.output_every : core.t_end, core.t_end);
  std::printf("\noutputs in %s/{%s}: diagnostics.csv, drop.pvd (+ drop_*.vtp), summary.csv, *.png\n"
              "open in ParaView: paraview %s/%s/drop.pvd  (colour by density, pressure, div_v, psi)\n",
              core.out.c_str(), results_.size() > 1 ? "cleaned,control" : results_[0].first.c_str(), core.out.c_str(),
              results_[0].first.c_str());
  return 0;
}

// cleaned | control side by side, coloured by pressure
std::vector<Scene::ParaViewStateFile> WaterDropScene::paraview_states(const std::vector<std::string>& runs) const {
  ParaViewStateFile state{"view.pvsm", {}};
  for (const std::string& r : runs) state.views.push_back({std::filesystem::path(r) / "drop.pvd", "pressure"});
  return {state};
}

}  // namespace sphark
