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
  // The cheapest stepper measured to keep the time error of every reported number below 1/10 of
  // the spatial error (docs/water_drop.md, "Time integration of the main job"): the error
  // control alone, without the CFL cap, which held the old default (BS3, rtol 1e-4) at 5x the work.
  core.stepper = "ARKODE_ARK436L2SA_ERK_6_3_4";
  core.rtol = 1e-2;
  core.atol = 1e-6;
  core.step_cap = false;
  core.output_every = 0.002;
}

void WaterDropScene::add_options(OptionParser& p) {
  WaterDropConfig& sc = config_;
  p.add("--scheme", &scheme_,
        "seed: the seed's plain WCSPH (eqs. (26)-(28), no density diffusion: its cleaning comparison, runs seed_*); "
        "delta-sph: with density diffusion --delta (accurate against the exact ellipse); both",
        OneOf{{"seed", "delta-sph", "both"}});
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
  p.add("--delta", &sc.delta, "density diffusion coefficient of the delta-SPH runs (none: --scheme seed)", Positive{});
  p.add_switch("--diffusion-correction", &sc.diffusion_correction,
               "Antuono et al. (2010) correction of the density diffusion (off: Molteni & Colagrossi)");
  p.add("--sigma", &sc.clean_sigma, "cleaning damping sigma, tau = h / (sigma c_h)", NonNegative{});
  p.add("--cfl", &sc.cfl, "CFL number of the stability limit (leapfrog step, adaptive step cap)", Positive{});
  p.add("--skin", &sc.skin, "Verlet skin of the neighbour lists / support radius (cost only)", Range{0.0, 2.0});
  p.add("--initial-pressure", &initial_pressure_, "initial density from the exact pressure, or rho0 everywhere",
        OneOf{{"exact", "zero"}});
  p.add("--diagnostics-every", &diagnostics_every_, "time between diagnostics rows", Positive{});
}

void WaterDropScene::check_options(const OptionParser& p, CoreOptions& core, const RunControlOptions&, bool) {
  config_.exact_initial_pressure = initial_pressure_ == "exact";
  if (config_.spacing > 0.5 * config_.radius) p.fail("--spacing", "must be at most half the radius");
  if (scheme_ == "seed" && p.was_given("--delta")) p.fail("--delta", "--scheme seed has no density diffusion");
  limit_to_t_end(p, "--diagnostics-every", diagnostics_every_, core.t_end);
}

namespace {
constexpr std::string_view kSeedPrefix = "seed_";  // the runs of the seed's plain WCSPH
bool is_seed_run(const std::string& run) { return run.rfind(kSeedPrefix, 0) == 0; }
bool is_cleaned_run(const std::string& run) { return run.size() >= 7 && run.compare(run.size() - 7, 7, "cleaned") == 0; }
}  // namespace

// The seed's pair first (its cleaning comparison), then delta-SPH's (its accuracy).
std::vector<std::string> WaterDropScene::run_names() const {
  std::vector<std::string> prefixes, runs;
  if (scheme_ != "delta-sph") prefixes.emplace_back(kSeedPrefix);
  if (scheme_ != "seed") prefixes.emplace_back("");
  for (const std::string& prefix : prefixes) {
    if (cleaning_ != "off") runs.push_back(prefix + "cleaned");
    if (cleaning_ != "on") runs.push_back(prefix + "control");
  }
  return runs;
}

void WaterDropScene::check_restart_run(const OptionParser& p, const std::string& run) const {
  if (cleaning_ != "both" && (cleaning_ == "on") != is_cleaned_run(run))
    p.fail("--cleaning", cleaning_ + " contradicts the checkpoint (a " + run + " run)");
  if (scheme_ != "both" && (scheme_ == "seed") != is_seed_run(run))
    p.fail("--scheme", scheme_ + " contradicts the checkpoint (a " + run + " run)");
}

WaterDropConfig WaterDropScene::config_of(const std::string& run) const {
  WaterDropConfig c = config_;
  c.cleaning = is_cleaned_run(run);
  if (is_seed_run(run)) c.delta = 0;  // seed 000, eqs. (26)-(28) alone
  return c;
}

std::string WaterDropScene::scene_text(const std::string& run) const { return sphark::scene_text(config_of(run)); }

std::unique_ptr<SceneRun> WaterDropScene::make_run(const std::string& run, const CoreOptions& core) {
  return std::make_unique<DropRun>(config_of(run), diagnostics_every_, core.output_every, world());
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
  std::printf("%-13s %s t=%.4g  particles %zu  wall %.1f s  %s\n", label.c_str(), s.loop.ok() ? "ok    " : "FAILED",
              s.loop.t_reached, s.particles, s.loop.wall_seconds, format_stats(s.loop.stats).c_str());
  std::printf("              max semi-axis error %.2f%% (t=%.4f), at first squeeze %.2f%%, <mean|div v|>_t %.4g,"
              " max density error %.3g%%, KE(end) %.6g, energy drift %.3g%%, neighbour builds %ld\n",
              100 * s.max_semi_axis_error, s.time_of_max_error, 100 * s.squeeze_error, s.mean_abs_div_v_time_avg,
              100 * s.max_rel_density_error, s.kinetic_energy_end, 100 * s.total_energy_drift, s.neighbour_builds);
  if (!s.loop.ok()) std::printf("              reason: %s\n", s.loop.failure.c_str());
}
}  // namespace

namespace {
Real frame_interval(const CoreOptions& core) { return core.output_every > 0 ? core.output_every : core.t_end; }
}  // namespace

std::vector<PythonJob> WaterDropScene::run_pictures(const std::string& run, const CoreOptions& core) const {
  return drop_run_pictures(core.out, run, frame_interval(core), core.t_end);
}

int WaterDropScene::report(const CoreOptions& core, const std::vector<std::string>&, bool all_ok) {
  if (results_.empty() || world().rank() != 0) return 0;  // distributed: rank 0 reports
  if (!all_ok) {  // the failed or stopped runs' summaries only
    for (const auto& [label, s] : results_)
      if (!s.loop.ok()) print_summary(label, s);
    return 0;
  }
  std::printf("\nwater drop, %s, rtol %g, atol %g, dt %g, t_end %g\n", core.stepper.c_str(), core.rtol, core.atol,
              core.dt, core.t_end);
  for (const auto& [label, s] : results_) print_summary(label, s);
  write_drop_summary(core.out, results_);
  if (core.render) {  // (distributed: rank 0, from the parallel frames)
    std::vector<std::string> pending;
    for (const auto& [label, s] : results_)
      if (run_pictures_pending(label)) pending.push_back(label);
    make_drop_pictures(core.out, results_, pending, frame_interval(core), core.t_end);
  }
  std::string runs;
  for (const auto& [label, s] : results_) runs += (runs.empty() ? "" : ",") + label;
  std::printf("\noutputs in %s/{%s}: diagnostics.csv, drop.pvd (+ drop_*.%s); summary.csv, *.png\n"
              "open in ParaView: cd %s && paraview --state=view.pvsm  (or paraview %s/%s/drop.pvd; colour by density,"
              " pressure, div_v, psi)\n",
              core.out.c_str(), runs.c_str(), world().distributed() ? "pvtp, one .vtp per rank" : "vtp",
              core.out.c_str(), core.out.c_str(), results_.back().first.c_str());
  return 0;
}

// cleaned | control side by side, coloured by pressure
std::vector<Scene::ParaViewStateFile> WaterDropScene::paraview_states(const std::vector<std::string>& runs) const {
  ParaViewStateFile state{"view.pvsm", {}};
  for (const std::string& r : runs) state.views.push_back({std::filesystem::path(r) / "drop.pvd", "pressure"});
  return {state};
}

}  // namespace sphark
