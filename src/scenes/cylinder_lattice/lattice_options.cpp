// The options of the cylinder-lattice example and the scene text a restart must keep.
#include <exception>

#include "sphark/run/restart.hpp"
#include "sphark/scenes/cylinder_lattice/lattice_scene.hpp"

namespace sphark {

void CylinderLatticeScene::add_options(OptionParser& op) {
  LatticeParams& p = run_.params;
  op.add("--case", &case_, "single run, medium resolution (§8.1, Fig. 9) or low-resolution ensemble (§8.2, Fig. 10)",
         OneOf{{"single", "medium", "ensemble"}});
  op.add("--map", &map_,
         "ghost map: mirror (Psi0, eq. 15), nonlinear (Psi, eq. 21) or both (not with single); default: nonlinear "
         "for single, both otherwise",
         OneOf{{"mirror", "nonlinear", "both", "default"}});
  op.add("--bc", &bc_, "velocity condition of the ghosts", OneOf{{"free-slip", "no-slip"}});
  op.add("--particles", &particles_, "real particles (0: 100 for single/ensemble, 10000 for medium)", Range{0, 1e7});
  op.add("--v0", &p.v0, "driving velocity v0 of eq. (36) (single, medium)", NonNegative{});
  op.add("--v0-list", &v0s_, "driving velocities of the ensemble", NonNegative{});
  op.add("--seed", &seed_, "random initial configuration (single, medium)", Range{0, 4294967295.0});
  op.add("--seeds", &seeds_, "ensemble: seeds 1..N per map and v0", Range{1, 100000});
  op.add("--tau", &p.tau, "driving time tau of eq. (36); 0 switches the driving off", NonNegative{});
  op.add("--sound-speed", &p.sound_speed, "c_s of the Tait EOS", Positive{});
  op.add("--background-pressure", &p.background,
         "background pressure added to the Tait EOS, in units of c_s^2 rho0/7: P >= 0 for rho >= rho0 (1 - value)^(1/7); 0 = plain Tait",
         NonNegative{});
  op.add("--rho0", &p.rho0, "reference density of the Tait EOS", Positive{});
  op.add("--eta", &p.eta, "h = eta (m/rho)^(1/2), support 2h (Wendland C4)", Range{0.8, 3.0});
  op.add("--alpha", &p.alpha, "Monaghan artificial viscosity", NonNegative{});
  op.add("--cfl", &cfl_,
         "CFL number of the stability limit (leapfrog step, adaptive step cap); 0: 0.4 for the ensemble, 0.25 for "
         "single and medium (docs/time_integration.md, the lattice ensemble)",
         Range{0, 1.0});
  op.add("--accumulation", &p.accumulation, "accumulation event: a ghost's h below this fraction of eta dx",
         Range{0, 1});
  op.add("--min-separation", &run_.min_separation, "random start: minimum pair distance / dx", Range{0, 0.8});
}

void CylinderLatticeScene::check_options(const OptionParser& op, CoreOptions& core, const RunControlOptions& control,
                                         bool restarting) {
  LatticeParams& p = run_.params;
  if (case_ == "ensemble" && (control.checkpoint_every > 0 || restarting || control.inject_nan_at > 0))
    op.fail(control.checkpoint_every > 0 ? "--checkpoint-every" : restarting ? "--restart" : "--inject-nan-at",
            "not available with --case ensemble (many short runs; SIGINT keeps the runs done in ensemble.csv)");
  if (case_ == "ensemble" && world().distributed())
    op.fail("--case", "ensemble does not run distributed (many small serial runs); single and medium do");
  if (map_ == "default") map_ = case_ == "single" ? "nonlinear" : "both";
  if (core.stepper == "ark-imex") op.fail("--stepper", "ark-imex: the lattice system has no stiff part (use an ERK table or leapfrog)");
  if (cfl_ > 0 && cfl_ < 1e-3) op.fail("--cfl", std::to_string(cfl_) + " is below 1e-3 (0: the case's default)");
  p.cfl = cfl_ > 0 ? cfl_ : case_ == "ensemble" ? kEnsembleCfl : kResolvedCfl;
  if (case_ == "single" && map_ == "both") op.fail("--map", "'both' is not allowed with --case single (mirror or nonlinear)");
  maps_ = map_ == "both" ? std::vector<std::string>{"mirror", "nonlinear"} : std::vector<std::string>{map_};
  p.velocity = bc_ == "no-slip" ? VelocityBc::NoSlip : VelocityBc::FreeSlip;
  if (p.tau == 0) p.tau = -1;
  run_.particles = particles_ > 0 ? static_cast<std::size_t>(particles_) : (case_ == "medium" ? 10000 : 100);
  if (run_.particles < 20) op.fail("--particles", std::to_string(particles_) + " is too few (at least 20)");
  run_.seed = static_cast<unsigned>(seed_);
  run_.t_end = core.t_end;
  run_.stepper = stepper_options(core);  // the CFL number is --cfl (cfl_safety 1)
  stepper_ = core.stepper;
  if (core.output_every == 0 && case_ == "medium") core.output_every = std::min(0.5, core.t_end);  // frames
  try {  // parameters that only the scene can check: one line, exit 2, nothing written
    const LatticeParams q = lattice_params(p, run_.particles);
    if (2 * q.h_ref * 1.25 * 2 >= 2 * q.half_box)
      op.fail("--particles", std::to_string(run_.particles) + ": support radius 2h is not below half the box");
    (void)random_fluid_positions(q, run_.particles, run_.seed, run_.min_separation);
  } catch (const std::exception& e) {
    op.fail("--min-separation", e.what());
  }
}

std::string CylinderLatticeScene::scene_text(const std::string& map) const {
  const LatticeParams& p = run_.params;
  std::string text;
  append_key_value(text, "case", case_);
  append_key_value(text, "map", map);
  append_key_value(text, "bc", bc_);
  append_key_value(text, "particles", static_cast<Real>(run_.particles));
  append_key_value(text, "seed", static_cast<Real>(run_.seed));
  append_key_value(text, "min_separation", run_.min_separation);
  append_key_value(text, "relax_iterations", static_cast<Real>(run_.relax_iterations));
  append_key_value(text, "v0", p.v0);
  append_key_value(text, "tau", p.tau);
  append_key_value(text, "sound_speed", p.sound_speed);
  append_key_value(text, "background_pressure", p.background);
  append_key_value(text, "rho0", p.rho0);
  append_key_value(text, "eta", p.eta);
  append_key_value(text, "alpha", p.alpha);
  append_key_value(text, "cfl", p.cfl);
  append_key_value(text, "accumulation", p.accumulation);
  append_key_value(text, "stepper", stepper_);
  return text;
}

}  // namespace sphark
