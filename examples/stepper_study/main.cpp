// stepper_study (issue 7): which ARKODE method and tolerance gives a given accuracy for the
// least work, and where does each one fail? Work-precision matrix + stability limits of the
// time steppers on one scene. See README.md in this folder.
#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <exception>
#include <iostream>
#include <sstream>

#include "sphark/cli/options.hpp"
#include "sphark/core/profile.hpp"
#include "sphark/integrate/stepper.hpp"
#include "sphark/io/visualise.hpp"
#include "sphark/run/cost_estimate.hpp"
#include "sphark/run/signals.hpp"
#include "sphark/run/time_loop.hpp"  // kStepFloorFraction
#include "study.hpp"

using namespace sphark;

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

// Accepts ERK short forms: "DORMAND_PRINCE_7_4_5" for "ARKODE_DORMAND_PRINCE_7_4_5".
std::vector<std::string> method_list(const OptionParser& p, const std::string& option, const std::string& text,
                                     bool adaptive_only, bool allow_leapfrog) {
  std::vector<std::string> out;
  const auto tables = erk_table_names();
  for (std::string m : split(text)) {
    if (std::find(tables.begin(), tables.end(), m) == tables.end() &&
        std::find(tables.begin(), tables.end(), "ARKODE_" + m) != tables.end())
      m = "ARKODE_" + m;
    const bool erk = std::find(tables.begin(), tables.end(), m) != tables.end();
    if (!erk && m != "ark-imex" && !(allow_leapfrog && (m == "leapfrog" || m == "leapfrog-rev")))
      p.fail(option, "unknown method '" + m + "'");
    if (erk && adaptive_only && !erk_table_has_embedding(m)) p.fail(option, "'" + m + "' has no embedding (no adaptive steps)");
    out.push_back(m);
  }
  return out;
}

// The study runs its scene many times over: a scene that would not fit in memory is refused
// before it is built (run/cost_estimate.hpp). Every study scene is 2D on a unit domain, so its
// particles scale as spacing^-2: a probe at the spacing of ~kProbeParticles particles measures
// them and the bytes per particle of its reference run.
void check_study_size(const OptionParser& p, const std::string& scene_name, const StudySceneOptions& so,
                      const StudySettings& s) {
  const Real probe_spacing = std::sqrt(kPi / kProbeParticles);
  if (!(so.spacing > 0) || so.spacing >= probe_spacing) return;
  StudySceneOptions po = so;
  po.spacing = probe_spacing;
  const std::unique_ptr<StudyScene> probe_scene = make_study_scene(scene_name, po);
  const ProbeMeasurement m = measure_probe([&] {
    ProbeSubject subject;
    std::shared_ptr<StudyProblem> problem = probe_scene->build();
    subject.system = &problem->system();
    subject.y0 = problem->y0();
    subject.stepper = study_stepper_options(s.reference, *problem, *probe_scene, s.limits);
    subject.particles = problem->system().state_layout() ? problem->system().state_layout()->particles() : 0;
    subject.owner = problem;
    return subject;
  }, probe_scene->t_end());
  const CostEstimate e = estimate_memory(m.particles * (probe_spacing / so.spacing) * (probe_spacing / so.spacing), m);
  if (!e.fits()) p.fail("--spacing", memory_refusal(e));
}

// Fixed steps below the step floor (kStepFloorFraction x t_end) would never end: refused.
void check_fixed_steps(const OptionParser& p, const StudyScene& scene, const StudySettings& s) {
  const Real floor = kStepFloorFraction * scene.t_end();
  const auto check = [&](const char* option, const std::vector<Real>& cfls) {
    for (Real cfl : cfls)
      if (!(cfl * scene.cfl_unit() >= floor)) {
        char why[200];
        std::snprintf(why, sizeof why, "CFL %.3g gives dt=%.3g, below the step floor %.3g (%.0e x --t-end %.3g)", cfl,
                      cfl * scene.cfl_unit(), floor, kStepFloorFraction, scene.t_end());
        p.fail(option, why);
      }
  };
  if (!s.fixed_methods.empty()) check("--fixed-cfls", s.fixed_cfls);
  if (!s.leapfrog_methods.empty()) check("--leapfrog-cfls", s.leapfrog_cfls);
  // the reference run (and every capped case) takes steps of at most cap_cfl x the CFL unit
  check("--cap-cfl", {s.limits.cap_cfl});
  // a stability trial takes horizon / dt whole steps, down to CFL min_cfl
  const Real horizon = s.stability.horizon > 0 ? s.stability.horizon : scene.t_end();
  const Real steps = horizon / (s.stability.min_cfl * scene.cfl_unit());
  if (s.stability_run && !(steps <= 1 / kStepFloorFraction)) {
    char why[200];
    std::snprintf(why, sizeof why, "%.3g: a trial at CFL %.3g would take %.3g steps (at most %.0e)", horizon,
                  s.stability.min_cfl, steps, 1 / kStepFloorFraction);
    p.fail("--stability-horizon", why);
  }
}

// The study's settings with their defaults before the command line.
StudySettings default_study_settings() {
  StudySettings s;
  s.rtols = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
  s.fixed_cfls = {0.1, 0.2, 0.4, 0.8};
  s.leapfrog_cfls = {0.025, 0.05, 0.1, 0.2, 0.4, 0.8};
  return s;
}

// The command line: the scene's options, the study's settings and the texts that become its
// method lists and modes once parsed (settle_method_lists).
struct StudyOptions {
  std::string scene_name = "drop";
  std::filesystem::path out;
  StudySceneOptions so;
  StudySettings s = default_study_settings();
  std::string adaptive = "HEUN_EULER_2_1_2,BOGACKI_SHAMPINE_4_2_3,ZONNEVELD_5_3_4,DORMAND_PRINCE_7_4_5,VERNER_8_5_6,"
                         "FEHLBERG_13_7_8,ark-imex";
  std::string fixed = "BOGACKI_SHAMPINE_4_2_3,DORMAND_PRINCE_7_4_5,ark-imex";
  std::string stability = "all";
  std::string modes = "capped,uncapped";
  std::string what = "all";
  std::string leapfrogs = "leapfrog,leapfrog-rev";
  int threads = 1;
  bool render = true;
  Real ref_rtol = s.reference.rtol;
  bool profile = false;
};

void add_study_options(OptionParser& p, StudyOptions& o) {
  StudySceneOptions& so = o.so;
  StudySettings& s = o.s;
  p.add("--scene", &o.scene_name, "scene", OneOf{study_scene_names()});
  p.add("--out", &o.out, "output directory (default out/stepper_study/<scene>)", "DIR");
  p.add("--spacing", &so.spacing, "particle spacing (0: scene default; drop 0.08 = 484 particles, disc 0.08 = 484, orszag_tang 1/16 = 16 x 18)", NonNegative{});
  p.add("--t-end", &so.t_end, "end time (0: scene default; drop 0.025, disc 10, orszag_tang 0.5)", NonNegative{});
  p.add("--outputs", &so.outputs, "comparison times, evenly spaced to t_end (0: scene default: drop 25, disc 20, orszag_tang 10)", Range{0, 10000});
  p.add("--what", &o.what, "what to run", OneOf{{"all", "matrix", "stability"}});
  p.add("--methods", &o.adaptive, "adaptive methods (ERK tables with an embedding, ark-imex), comma-separated; 'none'");
  p.add("--modes", &o.modes, "adaptive modes: capped (dt <= cap-cfl x CFL unit), uncapped, or both", OneOf{{"capped", "uncapped", "capped,uncapped"}});
  p.add("--rtols", &s.rtols, "relative tolerances of the adaptive runs", Positive{});
  p.add("--cap-cfl", &s.limits.cap_cfl, "CFL number of the step cap of capped adaptive runs", Positive{});
  p.add("--fixed-methods", &o.fixed, "methods run at every --fixed-cfls (ERK tables, ark-imex; 'none')");
  p.add("--fixed-cfls", &s.fixed_cfls, "CFL numbers of the fixed-step runs", Positive{});
  p.add("--leapfrog-cfls", &s.leapfrog_cfls, "CFL numbers of the leapfrog runs", Positive{});
  p.add("--leapfrog-methods", &o.leapfrogs, "leapfrog variants run at every --leapfrog-cfls (leapfrog, leapfrog-rev; 'none')");
  p.add("--reference-rtol", &o.ref_rtol, "rtol of the reference run (VERNER_8_5_6) and its check (FEHLBERG_13_7_8)", Positive{});
  p.add("--max-rhs", &s.limits.max_rhs_evals, "stop a run after this many RHS evaluations", Positive{});
  p.add("--stability-methods", &o.stability, "methods of the stability bisection ('all': every ERK table, ark-imex, leapfrog)");
  p.add("--stability-horizon", &s.stability.horizon, "horizon of a stability trial (0: t_end)", NonNegative{});
  p.add("--energy-tolerance", &s.stability.energy_tolerance, "blow-up criterion: |E - E0| > tol |E0|", Positive{});
  p.add("--bisections", &s.stability.iterations, "bisection steps after bracketing", NonNegative{});
  p.add("--threads", &o.threads, "OpenMP threads (1: CPU time = work of one core)", Positive{});
  p.add_flag("--no-render", &o.render, "do not draw the charts", false);
  p.add_flag("--resume", &s.resume, "keep the rows of existing work_precision.csv / stability.csv and skip their cases");
  p.add("--raise-sigint-after", &s.raise_sigint_after,
        "testing aid: the study sends itself SIGINT after this many matrix cases (0 = never)", NonNegative{});
  p.add_flag("--profile", &o.profile, "print the wall-time split (neighbours, density/h, forces, stepper, output)");
}

// The parsed texts as the settings' method lists, modes and output directory.
void settle_method_lists(const OptionParser& p, StudyOptions& o) {
  StudySettings& s = o.s;
  s.adaptive_methods = o.adaptive == "none" ? std::vector<std::string>{} : method_list(p, "--methods", o.adaptive, true, false);
  s.leapfrog_methods = o.leapfrogs == "none" ? std::vector<std::string>{} : split(o.leapfrogs);
  for (const std::string& m : s.leapfrog_methods)
    if (m != "leapfrog" && m != "leapfrog-rev") p.fail("--leapfrog-methods", "unknown leapfrog variant '" + m + "'");
  s.fixed_methods = o.fixed == "none" ? std::vector<std::string>{} : method_list(p, "--fixed-methods", o.fixed, false, false);
  if (o.stability == "all") {
    s.stability_methods = erk_table_names();
    s.stability_methods.push_back("ark-imex");
    s.stability_methods.push_back("leapfrog");
    s.stability_methods.push_back("leapfrog-rev");
  } else {
    s.stability_methods = method_list(p, "--stability-methods", o.stability, false, true);
  }
  for (const std::string& m : split(o.modes)) s.adaptive_modes.push_back(m == "capped" ? StudyMode::Capped : StudyMode::Uncapped);
  s.reference.rtol = s.reference_check.rtol = o.ref_rtol;
  s.matrix = o.what != "stability";
  s.stability_run = o.what != "matrix";
  if (o.out.empty()) o.out = std::filesystem::path("out/stepper_study") / o.scene_name;
  s.out = o.out;
}

// Builds the scene (refused if too large), runs the matrix and the stability limits, draws the
// charts; the exit code.
int run_study(const OptionParser& p, StudyOptions& o) {
  const StudySettings& s = o.s;
  o.threads = apply_thread_count(o.threads, p.program());
  std::unique_ptr<StudyScene> scene;
  try {
    check_study_size(p, o.scene_name, o.so, s);
    scene = make_study_scene(o.scene_name, o.so);
  } catch (const std::exception& e) {
    exit_usage_error(p.program(), "--scene", e.what());
  }
  check_fixed_steps(p, *scene, s);
  run_profile().enable(o.profile);
  prepare_output_dir(s.out, p.program());
  install_stop_handlers();  // SIGINT/SIGTERM: stop the current case (no row), keep the rows so far
  const auto start = std::chrono::steady_clock::now();
  std::printf("stepper_study: %s; CFL unit h/(c+|v|) = %.4g; output %s\n", scene->description().c_str(), scene->cfl_unit(),
              s.out.c_str());
  try {
    if (s.matrix && !run_work_precision(*scene, s)) return 3;  // the reference run failed (as a failed run: exit 3)
    if (s.stability_run) run_stability(*scene, s);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stepper_study: %s\n", e.what());
    return 1;
  }
  if (o.profile) run_profile().print(std::cout, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  if (const int sig = stop_requested()) {
    std::fprintf(stderr, "stepper_study: stopped by signal %d; %s has the rows done so far (continue with --resume)\n", sig,
                 (s.out / "work_precision.csv").c_str());
    return 128 + sig;
  }
  if (o.render && !run_python("work_precision.py", {"--dir", s.out.string()}, false)) return 1;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  StudyOptions o;
  OptionParser p("stepper_study", "work-precision charts and stability limits of the time steppers on one scene");
  add_study_options(p, o);
  p.parse_or_exit(argc, argv);
  settle_method_lists(p, o);
  return run_study(p, o);
}
