// Flow of a compressible liquid through a periodic lattice of cylinders (seed 004, §8): the
// medium-resolution comparison of the ghost maps (§8.1, Fig. 9) and the low-resolution ensemble
// of t_max = min{t_final, t_penetration, t_accumulation} (§8.2, eq. 37, Fig. 10).
// See README.md in this folder and docs/cylinder_lattice.md.
#include <cstdio>
#include <algorithm>
#include <exception>
#include <optional>
#include <string>

#include "cases.hpp"
#include "sphark/cli/options.hpp"
#include "sphark/core/profile.hpp"
#include "sphark/run/restart.hpp"
#include "sphark/run/signals.hpp"

using namespace sphark;

int main(int argc, char** argv) {
  const std::optional<Checkpoint> restart = load_restart_option(argc, argv, "cylinder_lattice");
  const std::vector<std::string> args = run_arguments("cylinder_lattice", argc, argv, restart ? &*restart : nullptr);
  cylinder_lattice::Settings s;
  s.core.out = "out/cylinder_lattice";
  s.core.t_end = 10;
  s.core.stepper = "leapfrog";
  s.core.output_every = 0;
  s.core.threads = 0;
  LatticeParams& p = s.run.params;
  std::string &kase = s.kase, map = "default", &bc = s.bc;
  long particles = 0, seed = 1;
  s.v0s = {0.05, 0.10, 0.15, 0.20, 0.25, 0.30, 0.35, 0.40, 0.45, 0.50, 0.55, 0.60, 0.65, 0.70, 0.75};

  OptionParser op("cylinder_lattice", "flow through a periodic lattice of cylinders with ghost walls (seed 004 §8)");
  add_core_options(op, s.core);
  op.add("--case", &kase, "single run, medium resolution (§8.1, Fig. 9) or low-resolution ensemble (§8.2, Fig. 10)",
         OneOf{{"single", "medium", "ensemble"}});
  op.add("--map", &map,
         "ghost map: mirror (Psi0, eq. 15), nonlinear (Psi, eq. 21) or both (not with single); default: nonlinear "
         "for single, both otherwise",
         OneOf{{"mirror", "nonlinear", "both", "default"}});
  op.add("--bc", &bc, "velocity condition of the ghosts", OneOf{{"free-slip", "no-slip"}});
  op.add("--particles", &particles, "real particles (0: 100 for single/ensemble, 10000 for medium)", Range{0, 1e7});
  op.add("--v0", &p.v0, "driving velocity v0 of eq. (36) (single, medium)", NonNegative{});
  op.add("--v0-list", &s.v0s, "driving velocities of the ensemble", NonNegative{});
  op.add("--seed", &seed, "random initial configuration (single, medium)", Range{0, 4294967295.0});
  op.add("--seeds", &s.seeds, "ensemble: seeds 1..N per map and v0", Range{1, 100000});
  op.add("--tau", &p.tau, "driving time tau of eq. (36); 0 switches the driving off", NonNegative{});
  op.add("--sound-speed", &p.sound_speed, "c_s of the Tait EOS", Positive{});
  op.add("--background-pressure", &p.background,
         "background pressure added to the Tait EOS, in units of c_s^2 rho0/7: P >= 0 for rho >= rho0 (1 - value)^(1/7); 0 = plain Tait",
         NonNegative{});
  op.add("--rho0", &p.rho0, "reference density of the Tait EOS", Positive{});
  op.add("--eta", &p.eta, "h = eta (m/rho)^(1/2), support 2h (Wendland C4)", Range{0.8, 3.0});
  op.add("--alpha", &p.alpha, "Monaghan artificial viscosity", NonNegative{});
  op.add("--cfl", &p.cfl, "CFL number of the stability limit (leapfrog step, adaptive step cap)", Range{1e-3, 1.0});
  op.add("--accumulation", &p.accumulation, "accumulation event: a ghost's h below this fraction of eta dx",
         Range{0, 1});
  op.add("--min-separation", &s.run.min_separation, "random start: minimum pair distance / dx", Range{0, 0.8});
  add_run_options(op, s.control, "<out>/single_<map>/ or <out>/<map>/checkpoint.bin (single, medium)");
  const std::vector<const char*> parse_argv = as_argv(args);
  op.parse_or_exit(static_cast<int>(parse_argv.size()), parse_argv.data());
  check_run_options(op, s.control, s.core);
  if (kase == "ensemble" && (s.control.checkpoint_every > 0 || restart || s.control.inject_nan_at > 0))
    op.fail(s.control.checkpoint_every > 0 ? "--checkpoint-every" : restart ? "--restart" : "--inject-nan-at",
            "not available with --case ensemble (many short runs; SIGINT keeps the runs done in ensemble.csv)");

  if (map == "default") map = kase == "single" ? "nonlinear" : "both";
  if (s.core.stepper == "ark-imex") op.fail("--stepper", "ark-imex: the lattice system has no stiff part (use an ERK table or leapfrog)");
  if (kase == "single" && map == "both") op.fail("--map", "'both' is not allowed with --case single (mirror or nonlinear)");
  s.maps = map == "both" ? std::vector<std::string>{"mirror", "nonlinear"} : std::vector<std::string>{map};
  p.velocity = bc == "no-slip" ? VelocityBc::NoSlip : VelocityBc::FreeSlip;
  if (p.tau == 0) p.tau = -1;
  s.run.particles = particles > 0 ? static_cast<std::size_t>(particles) : (kase == "medium" ? 10000 : 100);
  if (s.run.particles < 20) op.fail("--particles", std::to_string(particles) + " is too few (at least 20)");
  s.run.seed = static_cast<unsigned>(seed);
  s.run.t_end = s.core.t_end;
  s.run.stepper = stepper_options(s.core);
  if (s.core.stepper == "leapfrog") s.run.stepper.cfl_safety = 1;  // CFL number: --cfl
  if (s.core.output_every == 0 && kase == "medium") s.core.output_every = std::min(0.5, s.core.t_end);  // frames
  try {  // parameters that only the scene can check: one line, exit 2, nothing written
    const LatticeParams q = lattice_params(p, s.run.particles);
    if (2 * q.h_ref * 1.25 * 2 >= 2 * q.half_box)
      op.fail("--particles", std::to_string(s.run.particles) + ": support radius 2h is not below half the box");
    (void)random_fluid_positions(q, s.run.particles, s.run.seed, s.run.min_separation);
  } catch (const std::exception& e) {
    op.fail("--min-separation", e.what());
  }
  if (restart) {  // one map: the checkpoint's
    const std::string name = restart->text("run");
    if (map != "both" && map != name) op.fail("--map", map + " contradicts the checkpoint (map " + name + ")");
    s.maps = {name};
    check_restart_text(op, *restart, "scene", cylinder_lattice::scene_text(s, name), "scene parameters");
    check_restart_t_end(op, *restart, s.core.t_end);
  }
  run_profile().enable(s.core.profile);
  prepare_output_dir(s.core.out, op.program());
  if (kase != "ensemble") install_stop_handlers();
  s.argv.assign(args.begin() + 1, args.end());
  s.restart = restart ? &*restart : nullptr;
  if (kase != "ensemble") apply_thread_count(s.core.threads);
  try {
    if (kase == "single") return cylinder_lattice::run_single(s);
    if (kase == "medium") return cylinder_lattice::run_medium(s);
    return cylinder_lattice::run_ensemble_case(s);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cylinder_lattice: error: %s\n", e.what());
    return 1;
  }
}
