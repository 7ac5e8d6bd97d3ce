#pragma once
// Command-line plumbing of --restart FILE: a restarted run re-reads the options stored in the
// checkpoint and applies the ones given now on top (the parser's "last occurrence wins"), so
// `prog --restart out/checkpoint.bin --t-end 0.2` continues the same run further.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sphark/cli/options.hpp"
#include "sphark/core/types.hpp"
#include "sphark/run/checkpoint.hpp"

namespace sphark {

// The value of `name` in argv[1..argc) ("--name value" or "--name=value"; the last occurrence),
// or nullopt. A trailing "--name" without a value yields "" (the parser then reports it).
std::optional<std::string> find_option_value(int argc, const char* const* argv, const std::string& name);

// `args` without every occurrence of `name` and its value.
std::vector<std::string> without_option(const std::vector<std::string>& args, const std::string& name);

// argv[1..argc) as strings.
std::vector<std::string> arguments(int argc, const char* const* argv);

// [program] + stored + current: the argument list of a restarted run.
std::vector<std::string> restart_arguments(const std::string& program, const std::vector<std::string>& stored,
                                           const std::vector<std::string>& current);

// Pointers into `args` for an argc/argv-style parser (valid while `args` lives).
std::vector<const char*> as_argv(const std::vector<std::string>& args);

// ---- --restart in an example's main() ------------------------------------------------------

// The run-control options of a time-integrating example.
struct RunControlOptions {
  Real checkpoint_every = 0;      // --checkpoint-every T (0: only on failure or a stop signal)
  std::filesystem::path restart;  // --restart FILE (the file itself: load_restart_option, before parsing)
  Real inject_nan_at = 0;         // --inject-nan-at T (testing aid; 0 = never)
  int concurrent_runs = 1;        // --concurrent-runs N: runs side by side (run_scene_main; default: the scene's)
};
// Registers --checkpoint-every (its help says the checkpoint goes to `where`), --restart,
// --inject-nan-at and --concurrent-runs.
void add_run_options(OptionParser& p, RunControlOptions& o, const std::string& where);
// After parsing: --output-every and --checkpoint-every given by the user must not exceed
// --t-end (p.fail, exit 2); their defaults follow a shorter run (limit_to_t_end).
// Also checks --dt and --max-dt against the step floor (check_step_option).
void check_run_options(const OptionParser& p, RunControlOptions& o, CoreOptions& core);
// A fixed --dt below the step floor kStepFloorFraction x --t-end (run/time_loop.hpp), or one that
// does not advance t at --t-end (t + dt == t): p.fail("--dt", ...), exit 2.
void check_step_option(const OptionParser& p, const CoreOptions& core);
struct TimeLoopSettings;
// The run-control part of a time loop's settings: the checkpoint file and its interval, the
// checkpoint to resume from (nullptr: none) and the NaN injection of --inject-nan-at.
void apply_run_control(TimeLoopSettings& ts, const RunControlOptions& o, const Checkpoint* restart,
                       const std::filesystem::path& checkpoint);
// After the options (and any restart) are checked, before the first output: sets the thread
// count (clamped to the cores, core.threads updated; see apply_thread_count), switches --profile
// on, creates the output directory (one line + exit 2 if it cannot be written) and installs the
// SIGINT/SIGTERM stop handlers.
void start_run(CoreOptions& core, std::string_view program);

// The checkpoint named by --restart (nullopt without the option), loaded before anything is
// parsed or written. A missing value, an unreadable or corrupt file, one written by another
// program or one whose numbers cannot be a run's (checkpoint_number_problem): one line
// "<program>: --restart: ..." and exit 2.
std::optional<Checkpoint> load_restart_option(int argc, const char* const* argv, const std::string& program);
// Why a (well-formed) checkpoint's numbers cannot be a run's: a negative or non-finite time or
// last step, a non-finite scalar; nullopt if they can.
std::optional<std::string> checkpoint_number_problem(const Checkpoint& c);

// This run's argument list, [program] first: on a restart the checkpoint's stored options, then
// the ones given now (which override them), without --restart itself.
std::vector<std::string> run_arguments(const std::string& program, int argc, const char* const* argv,
                                       const Checkpoint* restart);

// "key=value\n" with the shortest text that reads back exactly (for checkpoint texts such as the
// scene parameters, which a restart must not change).
void append_key_value(std::string& text, const std::string& key, Real value);
void append_key_value(std::string& text, const std::string& key, const std::string& value);

// Checks of a restart against the checkpoint, each failing as p.fail(option, ...) (exit 2):
// the "key=value" text `stored_name` must equal `now` ("--restart: <what> cannot change on
// restart: checkpoint has k=v, this run k=w"), and t_end must lie after the checkpoint time.
void check_restart_text(const OptionParser& p, const Checkpoint& c, const std::string& stored_name,
                        const std::string& now, const std::string& what);
void check_restart_t_end(const OptionParser& p, const Checkpoint& c, Real t_end);

}  // namespace sphark
