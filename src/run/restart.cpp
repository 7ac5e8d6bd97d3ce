#include "sphark/run/restart.hpp"

#include "sphark/core/profile.hpp"
#include "sphark/run/signals.hpp"
#include "sphark/run/time_loop.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>
#include <vector>

namespace sphark {

std::optional<std::string> find_option_value(int argc, const char* const* argv, const std::string& name) {
  std::optional<std::string> value;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == name) {
      value = i + 1 < argc ? std::string(argv[i + 1]) : std::string();
      ++i;
    } else if (a.rfind(name + "=", 0) == 0) {
      value = a.substr(name.size() + 1);
    }
  }
  return value;
}

std::vector<std::string> without_option(const std::vector<std::string>& args, const std::string& name) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == name) {
      ++i;  // and its value
      continue;
    }
    if (args[i].rfind(name + "=", 0) == 0) continue;
    out.push_back(args[i]);
  }
  return out;
}

std::vector<std::string> arguments(int argc, const char* const* argv) {
  return std::vector<std::string>(argv + (argc > 0 ? 1 : 0), argv + argc);
}

std::vector<std::string> restart_arguments(const std::string& program, const std::vector<std::string>& stored,
                                           const std::vector<std::string>& current) {
  std::vector<std::string> out{program};
  out.insert(out.end(), stored.begin(), stored.end());
  out.insert(out.end(), current.begin(), current.end());
  return out;
}

std::vector<const char*> as_argv(const std::vector<std::string>& args) {
  std::vector<const char*> p;
  for (const auto& a : args) p.push_back(a.c_str());
  return p;
}

// ---- --restart in an example's main() ------------------------------------------------------

void add_run_options(OptionParser& p, RunControlOptions& o, const std::string& where) {
  p.add("--checkpoint-every", &o.checkpoint_every,
        "simulated time between checkpoints " + where + " (also written at the end); 0 = only on failure or "
        "SIGINT/SIGTERM",
        NonNegative{});
  p.add("--restart", &o.restart,
        "continue from a checkpoint (one run / variant: the checkpoint's; its options apply, the ones given override)",
        "FILE");
  p.add("--inject-nan-at", &o.inject_nan_at,
        "testing aid: the RHS turns non-finite from this time on (0 = never); exercises retry + clean failure",
        NonNegative{});
  p.add("--concurrent-runs", &o.concurrent_runs,
        "runs of this invocation side by side, each on --threads / N threads (1: one after the other; "
        "a restart, --profile and mpirun run one at a time)",
        Range{1, 64});
}

void apply_run_control(TimeLoopSettings& ts, const RunControlOptions& o, const Checkpoint* restart,
                       const std::filesystem::path& checkpoint) {
  ts.checkpoint = checkpoint;
  ts.checkpoint_every = o.checkpoint_every;
  ts.restart = restart;
  ts.inject_nan_at = o.inject_nan_at;
}

void check_run_options(const OptionParser& p, RunControlOptions& o, CoreOptions& core) {
  // a value the user gave must fit the run; a default follows it (issue #21: `--t-end 0.01`
  // alone is a valid short run)
  limit_to_t_end(p, "--output-every", core.output_every, core.t_end);
  limit_to_t_end(p, "--checkpoint-every", o.checkpoint_every, core.t_end);
  check_step_option(p, core);
}

namespace {
// A step (--dt, or the bound --max-dt) that does not advance t, or below the step floor.
void check_one_step(const OptionParser& p, std::string_view option, Real dt, Real t_end) {
  if (!(dt > 0)) return;
  const Real floor = kStepFloorFraction * t_end;
  char why[256];
  if (!(t_end + dt > t_end))
    std::snprintf(why, sizeof why, "%.3g does not advance t at --t-end %.3g (t + dt == t); the step floor is %.3g (%.0e x --t-end)",
                  dt, t_end, floor, kStepFloorFraction);
  else if (dt < floor)
    std::snprintf(why, sizeof why, "%.3g is below the step floor %.3g (%.0e x --t-end: a run of more than %.0e steps)",
                  dt, floor, kStepFloorFraction, 1 / kStepFloorFraction);
  else
    return;
  p.fail(option, why);
}
}  // namespace

void check_step_option(const OptionParser& p, const CoreOptions& core) {
  check_one_step(p, "--dt", core.dt, core.t_end);
  check_one_step(p, "--max-dt", core.max_dt, core.t_end);
  if (per_particle_stepper(core.stepper) && !(core.dt > 0) && !(core.max_dt > 0))
    p.fail("--stepper", core.stepper + " needs its top step: give --max-dt (the longest step; the particles' "
                                        "levels lie at power-of-two fractions of it) or --dt");
  if (core.dt > 0 && core.max_dt > 0 && core.max_dt < core.dt)
    p.fail("--max-dt", "below --dt: the fixed step --dt would take steps above this bound; give one of them");
  if (core.stepper.starts_with("mri-") && core.mri_levels > 2 && core.dt > 0 && core.mri_ratio < 2)
    p.fail("--mri-ratio", "must be >= 2 with --mri-levels > 2 and --dt (level k steps by --dt / ratio^k)");
}

std::optional<std::string> checkpoint_number_problem(const Checkpoint& c) {
  char why[160];
  if (!std::isfinite(c.t) || c.t < 0) return std::snprintf(why, sizeof why, "time %g is not a time of a run", c.t), why;
  if (!std::isfinite(c.last_dt) || c.last_dt < 0)
    return std::snprintf(why, sizeof why, "last step %g is not a step", c.last_dt), why;
  for (const auto& [name, v] : c.scalars)
    if (!std::isfinite(v)) return "its number '" + name + "' is " + std::to_string(v);
  return std::nullopt;
}

std::optional<Checkpoint> load_restart_option(int argc, const char* const* argv, const std::string& program) {
  const auto file = find_option_value(argc, argv, "--restart");
  if (!file) return std::nullopt;
  if (file->empty()) exit_usage_error(program, "--restart", "missing value (expected a checkpoint FILE)");
  Checkpoint c;
  try {
    c = load_checkpoint(*file);
  } catch (const std::exception& e) {
    exit_usage_error(program, "--restart", e.what());
  }
  if (c.program != program)
    exit_usage_error(program, "--restart", "'" + *file + "' was written by " + c.program + ", not " + program);
  if (const auto why = checkpoint_number_problem(c)) exit_usage_error(program, "--restart", "'" + *file + "': " + *why);
  return c;
}

std::vector<std::string> run_arguments(const std::string& program, int argc, const char* const* argv,
                                       const Checkpoint* restart) {
  std::vector<std::string> args = arguments(argc, argv);
  if (restart) return without_option(restart_arguments(program, restart->argv, args), "--restart");
  args.insert(args.begin(), program);
  return args;
}

void append_key_value(std::string& text, const std::string& key, Real value) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, value);
  ((text += key) += '=').append(buf, r.ptr) += '\n';
}

void append_key_value(std::string& text, const std::string& key, const std::string& value) {
  ((text += key) += '=') += value + '\n';
}

namespace {
// "key=value" lines as key -> value, in order.
std::vector<std::pair<std::string, std::string>> key_values(const std::string& text) {
  std::vector<std::pair<std::string, std::string>> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const std::size_t eq = line.find('=');
    out.emplace_back(line.substr(0, eq), eq == std::string::npos ? std::string() : line.substr(eq + 1));
  }
  return out;
}

const std::string* value_of(const std::vector<std::pair<std::string, std::string>>& kv, const std::string& key) {
  for (const auto& [k, v] : kv)
    if (k == key) return &v;
  return nullptr;
}
}  // namespace

// Key by key, so that a key one side lacks (a checkpoint of an older version) is named as such.
void check_restart_text(const OptionParser& p, const Checkpoint& c, const std::string& stored_name,
                        const std::string& now, const std::string& what) {
  const auto stored = key_values(c.text(stored_name)), current = key_values(now);
  auto shown = [](const std::string& key, const std::string* value) {
    return value ? key + "=" + *value : "no " + key;
  };
  for (const auto* side : {&current, &stored})
    for (const auto& [key, value] : *side) {
      const std::string *a = value_of(stored, key), *b = value_of(current, key);
      if (!a || !b || *a != *b)
        p.fail("--restart", what + " cannot change on restart: checkpoint has " + shown(key, a) + ", this run " + shown(key, b));
    }
}

void check_restart_t_end(const OptionParser& p, const Checkpoint& c, Real t_end) {
  if (c.t < t_end * (1 - 1e-12)) return;
  char why[128];
  std::snprintf(why, sizeof why, "%.9g is not after the checkpoint time %.9g", t_end, c.t);
  p.fail("--t-end", why);
}

void start_run(CoreOptions& core, std::string_view program) {
  core.threads = apply_thread_count(core.threads, program);
  run_profile().enable(core.profile);
  prepare_output_dir(core.out, program);
  install_stop_handlers();
}

}  // namespace sphark
