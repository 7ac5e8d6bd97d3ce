// The options every example takes, the output-directory check and the thread count.
#include <omp.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include "sphark/cli/options.hpp"
#include "sphark/integrate/stepper.hpp"  // erk_table_names
#include "sphark/io/csv_writer.hpp"        // temporary_sibling

namespace sphark {

void add_core_options(OptionParser& p, CoreOptions& o, std::vector<std::string> steppers) {
  p.add("--out", &o.out, "output directory, created with its parents", "DIR");
  p.add("--t-end", &o.t_end, "end time", Positive{});
  p.add("--stepper", &o.stepper, "time integrator", OneOf{std::move(steppers)});
  p.add("--rtol", &o.rtol, "relative tolerance of the adaptive step", Positive{});
  p.add("--atol", &o.atol, "absolute tolerance of the adaptive step", Positive{});
  p.add("--dt", &o.dt, "fixed time step, 0 = adaptive", NonNegative{});
  p.add_switch("--step-cap", &o.step_cap,
               "adaptive steps also bounded by the scheme's stable (CFL) step; off: by the error control alone");
  p.add("--max-dt", &o.max_dt, "upper bound on every step, 0 = none (the top step of leapfrog-blocks)", NonNegative{});
  p.add("--velocity-tolerance", &o.velocity_tolerance,
        "--stepper leapfrog or leapfrog-blocks: repeat the RHS (of the active particles) while the kicked velocities "
        "differ from the predicted ones by more than this x their rms (Phantom's tolv); 0 = off", NonNegative{});
  p.add("--mri-ratio", &o.mri_ratio, "--stepper mri-<table>: slow step / fast step", Positive{});
  p.add("--mri-levels", &o.mri_levels,
        "--stepper mri-<table>: levels of nested MRIStep (2 = slow/fast; more need --mri-ratio >= 2 with --dt)",
        Range{2, 8});
  p.add("--mri-fast-table", &o.mri_fast_table, "--stepper mri-<table>: the fast integrator's ERK table",
        OneOf{erk_table_names()});
  p.add("--partition-hysteresis", &o.partition_hysteresis,
        "--stepper leapfrog-blocks or mri-<table>: a particle moves to a longer step only when its stable step "
        "exceeds it by this fraction",
        NonNegative{});
  p.add("--block-cycles", &o.block_cycles,
        "--stepper leapfrog-blocks: top steps of --max-dt (fixed), or the way to each output in equal top steps "
        "of at most --max-dt, as many as give the fewest particle evaluations (fitted)",
        OneOf{{"fixed", "fitted"}});
  p.add("--output-every", &o.output_every,
        "simulated time between output frames, 0 = first and last only", NonNegative{});
  p.add("--threads", &o.threads, "OpenMP threads, 0 = OpenMP default", NonNegative{});
  p.add_flag("--no-render", &o.render, "do not render pictures at the end", false);
  p.add_flag("--profile", &o.profile,
             "print the wall-time split (neighbours, density/h, forces, stepper, output)");
}

void add_core_options(OptionParser& p, CoreOptions& o) {
  add_core_options(p, o, core_stepper_names());
}

std::vector<std::string> global_stepper_names() {
  std::vector<std::string> names = erk_table_names();
  names.push_back("ark-imex");
  names.push_back("leapfrog");
  names.push_back("leapfrog-rev");
  return names;
}

std::vector<std::string> core_stepper_names() {
  std::vector<std::string> names = global_stepper_names();
  names.push_back("leapfrog-blocks");
  for (const std::string& table : mri_table_names()) names.push_back("mri-" + table);
  return names;
}

bool per_particle_stepper(std::string_view stepper) {
  return stepper == "leapfrog-blocks" || stepper.starts_with("mri-");
}

StepperOptions stepper_options(const CoreOptions& o) {
  StepperOptions s;
  s.method = o.stepper;
  s.rtol = o.rtol;
  s.atol = {o.atol};
  s.fixed_dt = o.dt;
  s.cap_by_stability = o.step_cap;
  s.max_dt = o.max_dt;
  s.velocity_tolerance = o.velocity_tolerance;
  s.mri_ratio = o.mri_ratio;
  s.mri_levels = o.mri_levels;
  s.mri_fast_table = o.mri_fast_table;
  s.partition_hysteresis = o.partition_hysteresis;
  s.fit_block_cycles = o.block_cycles == "fitted";
  return s;
}

StepperOptions stepper_options(const CoreOptions& o, const OdeSystem& system, std::string_view program) {
  StepperOptions s = stepper_options(o);
  if (s.method == "ark-imex" && !system.has_stiff_diagonal()) {
    s.method = "ARKODE_DORMAND_PRINCE_7_4_5";
    if (!program.empty())
      std::fprintf(stderr, "%.*s: --stepper ark-imex: this run has no stiff part (no psi damping); using %s\n",
                 static_cast<int>(program.size()), program.data(), s.method.c_str());
  }
  if (s.velocity_tolerance > 0 && s.method != "leapfrog" && s.method != "leapfrog-blocks") {
    if (!program.empty())
      std::fprintf(stderr, "%.*s: --velocity-tolerance %g applies to --stepper leapfrog and leapfrog-blocks only; %s does not iterate its corrector\n",
                   static_cast<int>(program.size()), program.data(), s.velocity_tolerance, s.method.c_str());
    s.velocity_tolerance = 0;
  }
  return s;
}

void limit_to_t_end(const OptionParser& p, std::string_view option, Real& value, Real t_end) {
  const Real least = t_end / kMaxOutputs;
  if (value > t_end) {
    if (p.was_given(option)) p.fail(option, "must not exceed --t-end");
    value = t_end;
  } else if (value > 0 && value < least) {
    char why[160];
    std::snprintf(why, sizeof why, "%.3g gives more than %.0e outputs up to --t-end %.3g (at least %.3g)", value,
                  kMaxOutputs, t_end, least);
    if (p.was_given(option)) p.fail(option, why);
    value = least;
  }
}

int apply_thread_count(int threads, std::string_view program) {
  const int cores = std::max(1, omp_get_num_procs());
  const int wanted = threads > 0 ? threads : omp_get_max_threads();
  if (wanted <= cores) {
    if (threads > 0) omp_set_num_threads(threads);
    return wanted;
  }
  const std::string what = threads > 0 ? "--threads " + std::to_string(threads)
                                        : "OMP_NUM_THREADS=" + std::to_string(wanted);
  std::fprintf(stderr, "%.*s: %s: more than the %d core%s of this machine; using %d\n", static_cast<int>(program.size()),
               program.data(), what.c_str(), cores, cores > 1 ? "s" : "", cores);
  omp_set_num_threads(cores);
  return cores;
}

namespace {
// "'<path>'", built stepwise (operator+("'", std::string) trips GCC 12's -Wrestrict).
std::string quoted(const std::filesystem::path& p) {
  std::string q = "'";
  q += p.string();
  q += '\'';
  return q;
}
}  // namespace

std::optional<std::string> output_dir_problem(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  if (dir.empty()) return "empty directory name";
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return "cannot create " + quoted(dir) + ": " + ec.message();
  if (!fs::is_directory(dir, ec)) return quoted(dir) + " is not a directory";
  // Probe: create and remove a file (access(2) is not reliable, e.g. when running as root on a
  // read-only mount).
  const fs::path probe = temporary_sibling(dir / "write_probe");
  std::FILE* f = std::fopen(probe.c_str(), "w");
  if (!f) return "cannot write in " + quoted(dir) + ": " + std::strerror(errno);
  std::fclose(f);
  fs::remove(probe, ec);
  return std::nullopt;
}

void prepare_output_dir(const std::filesystem::path& dir, std::string_view program) {
  if (auto problem = output_dir_problem(dir)) exit_usage_error(program, "--out", *problem);
}

}  // namespace sphark
