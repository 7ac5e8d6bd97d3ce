#pragma once
// A small typed command-line parser. Each option writes straight into the caller's variable
// (no string-keyed value store); the variable's value at add() time is the documented default.
//
//   Real t_end = 0.1;
//   OptionParser p("water_drop", "2D water drop with divergence cleaning");
//   p.add("--t-end", &t_end, "end time", Positive{});
//   p.parse_or_exit(argc, argv);  // --help: prints help, exit 0; bad input: one line, exit 2
//
// Syntax: "--name value" or "--name=value"; flags take no value. The last occurrence wins.
// Any bad input yields ONE line on stderr, e.g.
//   water_drop: --rtol: bad value 'abc' (expected a positive real number)
//
// Every parser also takes "--config FILE": the option values of a JSON file, either a run
// record (io/run_record.hpp: its "options" object) or a flat object {"t-end": 0.5, ...}, applied
// first, through the same checks, so options on the command line override them wherever they
// stand. A key that names no option, a value of the wrong JSON type or out of range gets the
// same one line and exit 2 as the command line, e.g.
//   water_drop: --t-end: bad value '-1' in config 'run.json' (expected a positive real number)
// Values given on the command line or in a config are "given" (was_given); the others keep
// their defaults, which a program may adapt to the run (e.g. --output-every to a short --t-end).
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/integrate/ode_system.hpp"
#include "sphark/integrate/stepper_options.hpp"
#include "sphark/io/json.hpp"

namespace sphark {

// Constraints for numeric options (reals are also always required to be finite).
struct Positive {};
struct NonNegative {};
struct Range {  // lo <= value <= hi
  Real lo, hi;
};
using NumberConstraint = std::variant<std::monostate, Positive, NonNegative, Range>;
// Allowed values of a string option (empty = any non-empty string).
struct OneOf {
  std::vector<std::string> values;
};

enum class ParseStatus { ok, help, usage_error };

// One option as a run record stores it: name without "--", type ("real", "integer", "string",
// "path", "real list", "integer list", "flag", "switch"), current value, and whether the user
// gave it (command line or config) or it is the default.
struct OptionRecord {
  std::string name;
  std::string type;
  Json value;
  bool given = false;
};

// Prints "<program>: <option>: <reason>" (or "<program>: <reason>" if option is empty) to
// stderr and exits with status 2.
[[noreturn]] void exit_usage_error(std::string_view program, std::string_view option,
                                   std::string_view reason);

class OptionParser {
 public:
  OptionParser(std::string program, std::string description);

  // Value options. Names must start with "--" (--help and --config are taken); throws
  // std::logic_error for a duplicate name or a default that violates its own constraint
  // (programmer errors).
  void add(std::string name, Real* target, std::string help, NumberConstraint c = {});
  void add(std::string name, int* target, std::string help, NumberConstraint c = {});
  void add(std::string name, long* target, std::string help, NumberConstraint c = {});
  void add(std::string name, std::string* target, std::string help, OneOf allowed = {});
  void add(std::string name, std::filesystem::path* target, std::string help,
           std::string metavar = "PATH");
  // Comma-separated lists ("--resolutions 25,50,100"); every element meets the constraint.
  void add(std::string name, std::vector<Real>* target, std::string help, NumberConstraint c = {});
  void add(std::string name, std::vector<int>* target, std::string help, NumberConstraint c = {});
  void add(std::string name, bool* target, std::string help) = delete;  // use flag / switch
  // "--name": sets *target = value_when_given (e.g. --no-render sets render = false).
  void add_flag(std::string name, bool* target, std::string help, bool value_when_given = true);
  // "--name on|off".
  void add_switch(std::string name, bool* target, std::string help);

  // Parses argv[1..argc). If any argument is --help (or -h): prints help() to stdout and
  // returns help. On bad input: prints one line to stderr and returns usage_error (targets
  // may be partly assigned).
  ParseStatus parse(int argc, const char* const* argv);
  ParseStatus parse(int argc, char** argv) {
    return parse(argc, const_cast<const char* const*>(argv));
  }
  // parse(), then exit(0) after --help and exit(2) after a usage error.
  void parse_or_exit(int argc, const char* const* argv);
  void parse_or_exit(int argc, char** argv) {
    parse_or_exit(argc, const_cast<const char* const*>(argv));
  }

  // For checks across options after parsing: one line naming the option, exit 2.
  [[noreturn]] void fail(std::string_view option, std::string_view reason) const;

  // Applies the option values of a JSON object (keys with or without "--"; a run record's
  // "options" object) as parse() does with --config; `source` names it in error lines. Prints
  // one line and returns usage_error on the first bad entry.
  ParseStatus apply_json(const Json& options, std::string_view source);
  // Reads FILE (a run record or a flat object) and applies it; usage_error with one line
  // "<program>: --config: ..." if it cannot be read or parsed, or records another program.
  ParseStatus apply_config_file(const std::filesystem::path& file);

  // Whether `name` ("--t-end") was given on the command line or in a config; std::logic_error
  // for a name that is no option.
  bool was_given(std::string_view name) const;
  // Every option in registration order, with its current value.
  std::vector<OptionRecord> records() const;
  // {"name": value, ...} of every option: what --config reads back.
  Json to_json() const;
  // The arguments of the last parse() (argv[1..argc)) and the config files it applied.
  const std::vector<std::string>& arguments() const { return arguments_; }
  const std::vector<std::filesystem::path>& config_files() const { return config_files_; }

  std::string help() const;
  const std::string& program() const { return program_; }

 private:
  enum class Kind { real, integer, string, path, real_list, integer_list, flag, on_off };
  struct Option {
    std::string name;
    std::string metavar;  // "REAL", "INT", "NAME", "DIR", "on|off", "" for flags
    std::string help;
    std::string default_text;
    std::string expected;  // "a positive real number", ...
    // Parses and assigns; returns false if the text is not acceptable. A flag takes "" (as
    // given) or "off" (as not given, from a config's false).
    std::function<bool(std::string_view)> assign;
    Kind kind = Kind::string;
    std::function<Json()> value;  // the target's current value
    bool given = false;
  };
  void add_option(Option o);
  const Option* find(std::string_view name) const;
  Option* find(std::string_view name);
  ParseStatus parse_arguments(int argc, const char* const* argv);
  // Prints "<program>: <option>: <reason>" to stderr; returns usage_error.
  ParseStatus report(std::string_view option, const std::string& reason) const;
  // A config value as the text assign() takes, or nullopt for the wrong JSON type.
  static std::optional<std::string> config_text(const Option& o, const Json& v);
  static const char* kind_name(Kind k);  // "real", "integer", ... (OptionRecord::type)

  std::string program_, description_;
  std::vector<Option> options_;
  std::vector<std::string> arguments_;
  std::vector<std::filesystem::path> config_files_;
};


// --- Options every example takes ----------------------------------------------------------
struct CoreOptions {
  std::filesystem::path out = "out";  // output directory
  Real t_end = 1;                     // end time
  std::string stepper = "ARKODE_DORMAND_PRINCE_7_4_5";  // ERK table | ark-imex | leapfrog[-rev]
  Real rtol = 1e-6;                   // adaptive-step relative tolerance
  Real atol = 1e-9;                   // adaptive-step absolute tolerance
  Real dt = 0;                        // fixed step; 0 = adaptive
  Real output_every = 0;              // simulated time between frames; 0 = first and last only
  int threads = 0;                    // OpenMP threads; 0 = OpenMP default
  bool render = true;                 // render PNGs at the end (--no-render turns off)
  bool profile = false;               // --profile: print the wall-time split (core/profile.hpp)
  bool step_cap = true;               // adaptive steps also bounded by the scheme's CFL step (--step-cap)
  // Multirate (issue #17): --max-dt (every method's step bound; the top step of leapfrog-blocks
  // and of the power-of-two MRIStep levels when --dt is 0), --mri-ratio and --mri-fast-table
  // (--stepper mri-<table>).
  Real max_dt = 0;
  // --velocity-tolerance: the leapfrog's corrector iterations (Phantom's tolv,
  // StepperOptions::velocity_tolerance); 0 = off.
  Real velocity_tolerance = 0;
  int mri_ratio = 4;
  int mri_levels = 2;
  std::string mri_fast_table = "ARKODE_ZONNEVELD_5_3_4";
  // --partition-hysteresis: a particle's level (leapfrog-blocks, mri-<table>) grows only with this
  // margin (StepperOptions::partition_hysteresis).
  Real partition_hysteresis = StepperOptions{}.partition_hysteresis;
  // --block-cycles fixed|fitted: leapfrog-blocks' top steps (StepperOptions::fit_block_cycles).
  std::string block_cycles = "fixed";
};

// Registers --out, --t-end, --stepper, --rtol, --atol, --dt, --step-cap, --max-dt, --velocity-tolerance, --mri-ratio,
// --mri-fast-table, --partition-hysteresis, --block-cycles, --output-every, --threads, --no-render, --profile with the current values of
// `o` as defaults. `steppers` is the list of valid
// --stepper names (it lives in integrate/); o.stepper must be one of them.
void add_core_options(OptionParser& p, CoreOptions& o, std::vector<std::string> steppers);
// The same with core_stepper_names().
void add_core_options(OptionParser& p, CoreOptions& o);

// Every --stepper name make_stepper() accepts: global_stepper_names(), then the per-particle
// steppers "leapfrog-blocks" and "mri-<table>" (mri_table_names()).
std::vector<std::string> core_stepper_names();
// The steppers with one step for every particle: erk_table_names(), "ark-imex", "leapfrog",
// "leapfrog-rev" (a scene whose system evaluates no particle subsets offers these only).
std::vector<std::string> global_stepper_names();
// Whether `stepper` gives each particle its own step ("leapfrog-blocks", "mri-<table>"): it then
// needs a top step, --max-dt (or --dt).
bool per_particle_stepper(std::string_view stepper);

// StepperOptions{} with method = stepper, rtol, atol = {atol}, fixed_dt = dt,
// cap_by_stability = step_cap, max_dt, velocity_tolerance, mri_ratio, mri_levels, mri_fast_table,
// partition_hysteresis, fit_block_cycles = (block_cycles == "fitted").
StepperOptions stepper_options(const CoreOptions& o);
// The same for one run of `system`: when --stepper ark-imex meets a run without a stiff part
// (e.g. no psi damping), says so in one line on stderr (unless `program` is empty) and uses
// ARKODE_DORMAND_PRINCE_7_4_5 for that run (a scene that runs several variants keeps going;
// nothing is switched silently). A velocity_tolerance > 0 with any other stepper than
// "leapfrog" is dropped with one line on stderr the same way.
StepperOptions stepper_options(const CoreOptions& o, const OdeSystem& system, std::string_view program);

// An interval option (e.g. --output-every; 0 = off) that must lie in [t_end / kMaxOutputs, t_end]:
// a value the user gave (was_given) outside it is an error ("<option>: must not exceed --t-end",
// "<option>: ... more than 1e6 outputs ...", exit 2); a default outside it follows the run
// (t_end for a short run, t_end / kMaxOutputs for a long one).
inline constexpr Real kMaxOutputs = 1e6;
void limit_to_t_end(const OptionParser& p, std::string_view option, Real& value, Real t_end);

// Sets the OpenMP thread count and returns it: `threads`, or OpenMP's default (OMP_NUM_THREADS)
// for 0, clamped to the cores this process may use (omp_get_num_procs(): its affinity mask) with
// one warning line "<program>: --threads 100000: more than the 2 cores of this machine; using 2".
// (Unclamped, libgomp 12 puts a record per thread on the stack when it starts a team: 100000
// threads overflow the 8 MB stack, a segmentation fault.)
int apply_thread_count(int threads, std::string_view program = "sphark");

// Why `dir` cannot be used as an output directory (after trying to create it and its parents
// and to write a probe file in it), or nullopt if it is fine.
std::optional<std::string> output_dir_problem(const std::filesystem::path& dir);
// output_dir_problem(), and on a problem: "<program>: --out: <reason>" on stderr, exit 2.
void prepare_output_dir(const std::filesystem::path& dir, std::string_view program);

}  // namespace sphark
