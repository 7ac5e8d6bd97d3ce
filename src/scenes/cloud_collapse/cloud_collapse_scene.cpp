#include "sphark/scenes/cloud_collapse/cloud_collapse_scene.hpp"

#include <algorithm>
#include <cmath>

#include "collapse_run.hpp"
#include "sphark/run/restart.hpp"

namespace sphark {

std::string CloudCollapseScene::description() const {
  return "magnetised molecular cloud core collapse (seed 000 IV-C, Figs. 4-6): 1 M_sun, Omega, B for mass-to-flux 5, "
         "barotropic EOS, self-gravity, a sink; --t-end, --dt, --max-dt, --output-every, --diagnostics-every, "
         "--checkpoint-every and --step-floor in units of the free-fall time t_ff";
}

void CloudCollapseScene::set_defaults(CoreOptions& core) {
  core.out = "out/cloud_collapse";
  core.t_end = 1.1;           // t_ff
  core.output_every = 0.05;   // t_ff
  core.stepper = "leapfrog";  // dt = min(Courant, force criterion): one RHS per step
  // Phantom's corrector iterations: without them the 8,486-particle cleaned run fails at 1.0735
  // t_ff (docs/cloud_collapse.md); with them the 2,502-particle run costs 8.5 % more evaluations.
  core.velocity_tolerance = 0.1;
  // leapfrog-blocks: a particle takes a longer step as soon as its grid aligns (Phantom's rule):
  // 4.2 % fewer particle evaluations and 12 % fewer events to 1.1 t_ff than with the margin 0.25
  // at 8,486 particles, the same sink and curves (docs/time_integration.md, session 30).
  core.partition_hysteresis = 0;
  // leapfrog-blocks: the way to each output in as many equal cycles as fit the particles' steps
  // best (StepperOptions::fit_block_cycles): at 8,486 particles to 1.1 t_ff 4.1 % fewer particle
  // evaluations and 3.3 % fewer events than cycles of --max-dt (docs/time_integration.md, session 31).
  core.block_cycles = "fitted";
  core.rtol = 1e-4;
  core.atol = 1e-8;
}

void CloudCollapseScene::add_options(OptionParser& p) {
  std::vector<std::string> variants = cloud_collapse_variants();
  variants.push_back("both");
  p.add("--variant", &variant_, "div B control (both: cleaning+resistivity, then none)", OneOf{variants});
  p.add("--particles", &particles_,
        "particles in the sphere requested (the ambient adds ~0.476 x; below 1000 the ambient's smoothing "
        "lengths exceed half the box)",
        Range{1000, 1e8});
  p.add("--mass", &params_.mass_msun, "sphere mass [M_sun]", Range{1e-3, 1e3});
  p.add("--radius", &params_.radius_cm, "sphere radius [cm]", Range{1e14, 1e19});
  p.add("--sound-speed", &params_.sound_speed_cm_s, "isothermal sound speed of the sphere [cm/s]", Range{1e3, 1e7});
  p.add("--omega", &params_.omega_rad_s, "solid-body rotation rate about z [rad/s]", Range{0, 1e-10});
  p.add("--mass-to-flux", &params_.mass_to_flux, "mass-to-flux ratio in units of the critical", Range{0.1, 1e4});
  p.add("--contrast", &params_.density_contrast, "sphere / ambient density", Range{1, 1e4});
  p.add("--rho-sink", &params_.rho_sink_g_cm3, "sink creation density [g/cm^3]", Range{1e-16, 1});
  p.add("--r-acc", &params_.accretion_radius_cm, "sink accretion radius [cm]", Range{1e10, 1e17});
  p.add("--force-sink-above", &params_.forced_sink_factor,
        "make the densest gas a sink past the creation checks once it is this many times rho_sink "
        "(Phantom's f_crit_override; 0: never)",
        NonNegative{});
  p.add("--alpha", &params_.alpha_visc, "artificial viscosity", Range{0, 10});
  p.add("--alpha-b", &params_.alpha_b, "artificial resistivity of cleaning+resistivity", Range{0, 10});
  p.add("--sigma", &params_.sigma, "cleaning damping, 1/tau = sigma c_h / h", Range{0, 10});
  p.add("--overclean", &params_.overclean, "c_h = overclean x fast speed", Range{1, 100});
  p.add_flag("--local-ch", &local_ch_, "each particle's own c_h (its fast speed) instead of one global c_h");
  p.add("--ch-spread", &params_.ch_spread,
        "--local-ch: each particle's c_h the largest within this many kernel supports (0: its own)", Range{0, 16});
  p.add("--step-floor", &params_.step_floor_tff, "the run fails (exit 3) when its steps stay below this [t_ff]",
        Range{1e-12, 1e-2});
  p.add_flag("--no-tensile-correction", &no_tensile_correction_, "leave out the correction (9) of the Maxwell stress");
  p.add("--tensile-exclusion", &params_.tensile_exclusion,
        "leave out the correction (9) for gas within this many accretion radii of a sink (0: nowhere)", Range{0, 100});
  p.add("--tensile-beta", &params_.tensile_beta_none,
        "apply the correction (9) whole below plasma beta 2, less above, none above this beta (Phantom: 10; 0: at every beta)",
        Range{0, 1e6});
  p.add("--courant", &params_.courant, "Courant number of dt = C h / v_sig", Range{0.01, 1});
  p.add("--cleaning-courant", &params_.cleaning_courant,
        "the cleaning wave's own Courant number C_h: dt <= C_h h / (c_h + 3|v|), 0 = the Courant number", Range{0.0, 2.0});
  p.add("--gravity", &gravity_, "gravity solver", OneOf{{"tree", "direct"}});
  p.add("--theta", &params_.theta, "tree opening angle (the root's with --opening mass; default 0.5 fixed, 0.35 mass)",
        Range{0.05, 0.95});
  p.add("--opening", &opening_, "tree opening: one angle, or Dehnen's mass-dependent angle (docs/gravity.md)",
        OneOf{{"fixed", "mass"}});
  p.add("--subset-density", &subset_density_,
        "block steps: the inactive neighbours' densities, solved at each evaluation or predicted from their last solve",
        OneOf{{"solved", "predicted"}});
  p.add("--skin", &params_.skin,
        "Verlet skin of the neighbour lists, a fraction of the smallest support radius 2h (cost only: results do "
        "not depend on it, but with leapfrog-blocks and --subset-density solved)",
        Range{0.01, 2.0});
  p.add("--skin-own-fraction", &params_.skin_own_fraction,
        "the part of the skin in proportion to each h, the rest one length for all (cost only)", Range{0.0, 1.0});
  p.add("--diagnostics-every", &diagnostics_every_, "time between diagnostics rows [t_ff]", Positive{});
}

void CloudCollapseScene::check_options(const OptionParser& p, CoreOptions& core, const RunControlOptions&, bool) {
  limit_to_t_end(p, "--diagnostics-every", diagnostics_every_, core.t_end);  // both in t_ff
  if (params_.forced_sink_factor > 0 && params_.forced_sink_factor <= 1)
    p.fail("--force-sink-above", "must be 0 (never) or above 1 (a multiple of rho_sink)");
  params_.particles = static_cast<std::size_t>(particles_);
  params_.gravity = parse_gravity_solver(gravity_);
  params_.opening = parse_gravity_opening(opening_);
  params_.subset_density = parse_subset_density(subset_density_);
  if (!p.was_given("--theta")) params_.theta = default_theta(params_.opening);
  params_.local_ch = local_ch_;
  if (params_.ch_spread > 0 && !params_.local_ch) p.fail("--ch-spread", "spreads each particle's own c_h: give --local-ch too");
  params_.tensile_correction = !no_tensile_correction_;
  try {
    free_fall_time_ = cloud_numbers(params_).free_fall_time;
  } catch (const std::invalid_argument& e) {
    p.fail("--mass", e.what());
  }
}

Real CloudCollapseScene::time_unit() const { return free_fall_time_; }

std::vector<std::string> CloudCollapseScene::run_names() const {
  if (variant_ == "both") return {CloudCollapseParams{}.variant, "none"};  // a failing none does not stop the cleaned run
  return {variant_};
}

void CloudCollapseScene::check_restart_run(const OptionParser& p, const std::string& run) const {
  if (variant_ != "both" && variant_ != run) p.fail("--variant", variant_ + " contradicts the checkpoint (variant " + run + ")");
}

std::filesystem::path CloudCollapseScene::subdirectory(const std::string& run) const {
  return run == "cleaning+resistivity" ? "cleaning_resistivity" : run;
}

std::string CloudCollapseScene::scene_text(const std::string& run) const {
  std::string text;
  append_key_value(text, "variant", run);
  append_key_value(text, "particles", static_cast<Real>(params_.particles));
  append_key_value(text, "mass", params_.mass_msun);
  append_key_value(text, "radius", params_.radius_cm);
  append_key_value(text, "sound_speed", params_.sound_speed_cm_s);
  append_key_value(text, "omega", params_.omega_rad_s);
  append_key_value(text, "mass_to_flux", params_.mass_to_flux);
  append_key_value(text, "contrast", params_.density_contrast);
  append_key_value(text, "rho_sink", params_.rho_sink_g_cm3);
  append_key_value(text, "r_acc", params_.accretion_radius_cm);
  append_key_value(text, "force_sink_above", params_.forced_sink_factor);
  append_key_value(text, "alpha", params_.alpha_visc);
  append_key_value(text, "alpha_b", params_.alpha_b);
  append_key_value(text, "sigma", params_.sigma);
  append_key_value(text, "overclean", params_.overclean);
  append_key_value(text, "local_ch", params_.local_ch ? 1.0 : 0.0);
  if (params_.ch_spread > 0) append_key_value(text, "ch_spread", params_.ch_spread);
  append_key_value(text, "tensile_correction", params_.tensile_correction ? 1.0 : 0.0);
  append_key_value(text, "courant", params_.courant);
  if (params_.cleaning_courant > 0) append_key_value(text, "cleaning_courant", params_.cleaning_courant);
  append_key_value(text, "gravity", gravity_);
  append_key_value(text, "theta", params_.theta);
  if (params_.tensile_exclusion > 0) append_key_value(text, "tensile_exclusion", params_.tensile_exclusion);
  if (params_.tensile_beta_none > 0) append_key_value(text, "tensile_beta", params_.tensile_beta_none);
  if (params_.opening != GravityOpening::Fixed) append_key_value(text, "opening", opening_);  // old checkpoints restart
  append_key_value(text, "step_floor", params_.step_floor_tff);
  append_key_value(text, "subset_density", subset_density_);
  return text;
}

std::unique_ptr<SceneRun> CloudCollapseScene::make_run(const std::string& run, const CoreOptions&) {
  CloudCollapseParams p = params_;
  p.variant = run;
  return std::make_unique<CollapseRun>(p, diagnostics_every_ * free_fall_time_);
}

// The ambient lattice adds (L^3 - 4/3 pi R^3) / (4/3 pi R^3) / contrast particles per sphere particle.
Real CloudCollapseScene::predicted_particles(const std::string&) const {
  const Real sphere = 4.0 / 3.0 * 3.14159265358979323846;
  const Real box = std::pow(params_.box_over_radius, 3);
  return static_cast<Real>(particles_) * (1 + std::max<Real>(box - sphere, 0) / sphere / params_.density_contrast);
}

std::unique_ptr<SceneRun> CloudCollapseScene::make_probe_run(const std::string& run, const CoreOptions&,
                                                             Real particles) {
  CloudCollapseParams p = params_;
  p.variant = run;
  const Real per_sphere_particle = predicted_particles(run) / static_cast<Real>(std::max<long>(particles_, 1));
  p.particles = std::max<std::size_t>(1000, static_cast<std::size_t>(particles / per_sphere_particle));
  p.particles = std::min<std::size_t>(p.particles, params_.particles);
  return std::make_unique<CollapseRun>(p, diagnostics_every_ * free_fall_time_);
}

void CloudCollapseScene::finished(const std::string& run, SceneRun& r, const TimeLoopResult& result) {
  auto& collapse = static_cast<CollapseRun&>(r);
  collapse.write_final_products();
  summaries_.emplace_back(run, collapse_summary(run, collapse, result));
}

std::vector<Scene::ParaViewStateFile> CloudCollapseScene::paraview_states(const std::vector<std::string>& runs) const {
  std::vector<ParaViewStateFile> states;
  for (const std::string& r : runs) states.push_back({subdirectory(r) / "view.pvsm", {{"collapse.pvd", "density"}}});
  return states;
}

}  // namespace sphark
