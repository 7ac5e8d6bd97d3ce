#include "sphark/scenes/gravitating_sphere/gravitating_sphere_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "sphark/analytic/free_fall.hpp"
#include "sphark/diagnostics/spmhd_diagnostics.hpp"
#include "sphark/io/csv_writer.hpp"
#include "sphark/io/visualise.hpp"
#include "sphark/run/restart.hpp"
#include "sphark/scenes/gravitating_sphere/gravitating_sphere_run.hpp"

namespace sphark {

namespace {

const Real kUniformFreeFall = free_fall_time(3 / (4 * kPi));  // t_ff of the uniform sphere, G = M = R = 1

}  // namespace

std::string GravitatingSphereScene::description() const {
  return "self-gravitating gas sphere (issue #15): cold uniform collapse against the exact free fall, or the Evrard "
         "collapse; G = M = R = 1";
}

void GravitatingSphereScene::set_defaults(CoreOptions& core) {
  core.out = "out/gravitating_sphere";
  core.t_end = 0.9 * kUniformFreeFall;  // uniform; evrard: 3 (check_options)
  core.stepper = "leapfrog";            // dt = min(Courant, force criterion)
  core.output_every = 0.1;
  core.rtol = 1e-4;
  core.atol = 1e-8;
}

void GravitatingSphereScene::add_options(OptionParser& p) {
  p.add("--sphere", &params_.profile, "density profile (--profile is the wall-time split)", OneOf{{"uniform", "evrard"}});
  p.add("--particles", &particles_, "particles requested (the lattice gives the nearest count it allows)",
        Range{100, 1e8});
  p.add_flag("--random", &params_.random, "random placement instead of the close-packed lattice");
  p.add("--u0", &params_.u0, "initial specific internal energy (0: 1e-4 uniform, 0.05 Evrard)", NonNegative{});
  p.add("--gamma", &params_.gamma, "adiabatic index", Range{1.001, 3});
  p.add("--theta", &params_.theta, "tree opening angle (the root's with --opening mass; default 0.5 fixed, 0.35 mass)",
        Range{0.05, 0.95});
  p.add("--opening", &opening_, "tree opening: one angle, or Dehnen's mass-dependent angle (docs/gravity.md)",
        OneOf{{"fixed", "mass"}});
  p.add("--gravity", &gravity_, "gravity solver", OneOf{{"tree", "direct"}});
  p.add("--alpha", &params_.alpha_visc, "artificial viscosity (default: 0 uniform, 1 Evrard)", NonNegative{});
  p.add("--courant", &params_.courant, "Courant number of dt = C h / v_sig", Range{0.01, 1});
  p.add("--sinks", &sinks_, "sink particles (created above --rho-sink, accreting within --r-acc)", OneOf{{"on", "off"}});
  p.add("--rho-sink", &params_.rho_sink, "sink creation density (code units; default 100 x the mean density 3/(4 pi))",
        Positive{});
  p.add("--r-acc", &params_.accretion_radius, "sink accretion radius (code units, R = 1; default 0.03: docs in README)",
        Range{1e-6, 1});
  p.add("--diagnostics-every", &diagnostics_every_, "time between diagnostics rows", Positive{});
}

void GravitatingSphereScene::check_options(const OptionParser& p, CoreOptions& core, const RunControlOptions&, bool) {
  if (params_.profile == "evrard" && !p.was_given("--t-end")) core.t_end = 3;
  // The uniform sphere has no shock before t_ff: artificial viscosity (no switch) would act on the
  // homologous compression alone and slow the collapse (3000 particles, alpha = 1: the 50 % radius
  // 14 % behind the free fall at 0.9 t_ff; alpha = 0: 2.2 %; docs/gravity.md).
  if (params_.profile == "uniform" && !p.was_given("--alpha")) params_.alpha_visc = 0;
  params_.particles = static_cast<std::size_t>(particles_);
  params_.sinks = sinks_ == "on";
  for (const char* o : {"--rho-sink", "--r-acc"})
    if (!params_.sinks && p.was_given(o)) p.fail(o, "needs --sinks on");
  params_.gravity = parse_gravity_solver(gravity_);
  params_.opening = parse_gravity_opening(opening_);
  if (!p.was_given("--theta")) params_.theta = default_theta(params_.opening);
  limit_to_t_end(p, "--diagnostics-every", diagnostics_every_, core.t_end);
}

std::string GravitatingSphereScene::scene_text(const std::string&) const {
  std::string text;
  append_key_value(text, "sphere", params_.profile);
  append_key_value(text, "particles", static_cast<Real>(params_.particles));
  append_key_value(text, "random", params_.random ? 1.0 : 0.0);
  append_key_value(text, "u0", params_.u0);
  append_key_value(text, "gamma", params_.gamma);
  append_key_value(text, "theta", params_.theta);
  if (params_.opening != GravityOpening::Fixed) append_key_value(text, "opening", opening_);  // old checkpoints restart
  append_key_value(text, "gravity", gravity_);
  append_key_value(text, "alpha", params_.alpha_visc);
  append_key_value(text, "courant", params_.courant);
  if (params_.sinks) {  // without sinks the text stays as before (old checkpoints restart)
    append_key_value(text, "sinks", "on");
    append_key_value(text, "rho_sink", params_.rho_sink);
    append_key_value(text, "r_acc", params_.accretion_radius);
  }
  return text;
}

std::unique_ptr<SceneRun> GravitatingSphereScene::make_run(const std::string&, const CoreOptions&) {
  return std::make_unique<GravitatingSphereRun>(params_, diagnostics_every_);
}

// The cost probe (run/cost_estimate.hpp): the same sphere with fewer particles.
std::unique_ptr<SceneRun> GravitatingSphereScene::make_probe_run(const std::string&, const CoreOptions&, Real particles) {
  GravitatingSphereParams p = params_;
  p.particles = std::min(p.particles, static_cast<std::size_t>(particles));
  return std::make_unique<GravitatingSphereRun>(p, diagnostics_every_);
}

void GravitatingSphereScene::finished(const std::string&, SceneRun& r, const TimeLoopResult& result) {
  if (params_.sinks) {
    const SinkEventLog& log = dynamic_cast<GravitatingSphereRun&>(r).sink_log();
    std::string refused;
    for (const auto& [check, count] : log.refusals) {
      refused += ' ';
      refused += to_string(check);
      refused += ' ';
      refused += std::to_string(count);
    }
    std::fprintf(stderr, "gravitating_sphere: sinks created %ld, gas accreted %ld, candidates refused:%s\n",
                 log.creations, log.accreted_particles, refused.empty() ? " none" : refused.c_str());
  }
  results_.push_back(result);
}

std::vector<Scene::ParaViewStateFile> GravitatingSphereScene::paraview_states(const std::vector<std::string>& runs) const {
  std::vector<ParaViewStateFile> states;
  for (const std::string& r : runs) states.push_back({std::filesystem::path(r) / "view.pvsm", {{"sphere.pvd", "density"}}});
  return states;
}

}  // namespace sphark
