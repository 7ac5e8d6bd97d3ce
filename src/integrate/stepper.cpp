// make_stepper (option validation and dispatch), the ERK table list, run-summary strings.
#include "sphark/integrate/stepper.hpp"

#include <arkode/arkode_butcher_erk.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "collective_checks.hpp"
#include "sphark/integrate/guarded_system.hpp"
#include "steppers.hpp"
#include "number_text.hpp"

namespace sphark {
namespace {

using detail::number_text;

// option=value: why, thrown as std::invalid_argument if !ok (on every rank at once when the
// run is distributed: the checks run in the same order everywhere).
void require(const StepperOptions& o, bool ok, const std::string& option, const std::string& value,
             const std::string& why) {
  detail::require_everywhere(o.communicator, ok, option + "=" + value + ": " + why);
}

bool is_erk(const std::string& method) {
  const auto names = erk_table_names();
  return std::find(names.begin(), names.end(), method) != names.end();
}

void validate_common(const OdeSystem& system, const StepperOptions& o) {
  const std::size_t n = system.size();
  require(o, o.rtol > 0, "rtol", number_text(o.rtol), "must be > 0");
  require(o, o.atol.empty() || o.atol.size() == 1 || o.atol.size() == n || (o.communicator.distributed() && n == 0),
          "atol", std::to_string(o.atol.size()) + " values",
          "give one value or one per state entry (" + std::to_string(n) + ")");
  Real worst_atol = 0;
  for (Real a : o.atol)
    if (!(a >= 0)) {
      worst_atol = a;
      break;
    }
  require(o, !(worst_atol < 0) && !std::isnan(worst_atol), "atol", number_text(worst_atol), "must be >= 0");
  require(o, o.fixed_dt >= 0, "fixed_dt", number_text(o.fixed_dt), "must be >= 0");
  require(o, o.max_dt >= 0, "max_dt", number_text(o.max_dt), "must be >= 0");
  require(o, o.min_dt >= 0, "min_dt", number_text(o.min_dt), "must be >= 0");
  require(o, o.initial_dt >= 0, "initial_dt", number_text(o.initial_dt), "must be >= 0");
  require(o, o.cfl_safety > 0, "cfl_safety", number_text(o.cfl_safety), "must be > 0");
  require(o, o.max_steps > 0, "max_steps", std::to_string(o.max_steps), "must be > 0");
}

void validate_leapfrog(OdeSystem& system, const StepperOptions& o, Real t0, const Real* y0) {
  const std::size_t n = system.size(), np = system.position_size();
  const std::size_t xp = system.position_offset(), vp = system.velocity_offset();
  const bool empty_rank = o.communicator.distributed() && n == 0;  // its blocks are empty
  require(o, np > 0 || empty_rank, "method", o.method,
          "the system declares no position block (position_size() == 0)");
  require(o, !(xp + np > n || vp + np > n || (xp < vp + np && vp < xp + np)) || empty_rank, "method", o.method,
          "position/velocity blocks overlap or exceed the state size");
  const Real stable = o.fixed_dt > 0 || o.max_dt > 0 ? 0 : system.max_stable_dt(t0, y0, nullptr);
  const std::string why = std::isnan(stable) && !system.last_error().empty() ? " (" + system.last_error() + ")" : "";
  require(o, o.fixed_dt > 0 || o.max_dt > 0 || std::isfinite(stable), "method", o.method,
          "needs fixed_dt, max_dt or a finite system max_stable_dt" + why);
}

// method "mri-<table>" (multirate, issue #17): the options MRIStep of SUNDIALS 6.4.1 needs.
void validate_mri(const OdeSystem& system, const StepperOptions& o) {
  const std::string table = o.method.substr(4);
  require(o, mri_table_order(table) > 0, "method", o.method,
          "unknown MRI coupling table (mri-ARKODE_MIS_KW3, mri-ARKODE_MRI_GARK_ERK33a, mri-ARKODE_MRI_GARK_ERK45a)");
  require(o, o.fixed_dt > 0 || o.max_dt > 0, "method", o.method,
          "MRIStep of SUNDIALS 6.4.1 takes fixed slow steps: set fixed_dt, or max_dt for power-of-two slow steps");
  require(o, o.mri_slow_fraction > 0 && o.mri_slow_fraction <= 1, "mri_slow_fraction",
          number_text(o.mri_slow_fraction), "must be in (0, 1]");
  require(o, o.mri_ratio >= 1, "mri_ratio", std::to_string(o.mri_ratio), "must be >= 1");
  require(o, o.mri_levels >= 2 && o.mri_levels <= 8, "mri_levels", std::to_string(o.mri_levels), "must be in 2..8");
  require(o, o.mri_levels == 2 || !(o.fixed_dt > 0) || o.mri_ratio >= 2, "mri_ratio", std::to_string(o.mri_ratio),
          "must be >= 2 with mri_levels > 2 and fixed_dt (level k steps by fixed_dt / mri_ratio^k)");
  require(o, is_erk(o.mri_fast_table), "mri_fast_table", o.mri_fast_table, "not an ERK table of SUNDIALS 6.4.1");
  require(o, o.partition_hysteresis >= 0, "partition_hysteresis", number_text(o.partition_hysteresis), "must be >= 0");
  require(o, system.supports_subsets(), "method", o.method,
          "the system cannot evaluate particle subsets (OdeSystem::supports_subsets)");
  require(o, system.num_roots() == 0, "method", o.method, "root finding is not supported by the multirate stepper");
  require(o, !o.communicator.distributed(), "method", o.method, "the multirate stepper is serial only");
}

// "leapfrog-blocks" (issue #17): a position block, a top step, the subset interface.
void validate_blocks(const OdeSystem& system, const StepperOptions& o) {
  const std::size_t n = system.size(), np = system.position_size();
  const std::size_t xp = system.position_offset(), vp = system.velocity_offset();
  require(o, np > 0, "method", o.method, "the system declares no position block (position_size() == 0)");
  require(o, !(xp + np > n || vp + np > n || (xp < vp + np && vp < xp + np)), "method", o.method,
          "position/velocity blocks overlap or exceed the state size");
  require(o, o.fixed_dt > 0 || o.max_dt > 0, "method", o.method, "needs the top step: set fixed_dt or max_dt");
  require(o, o.partition_hysteresis >= 0, "partition_hysteresis", number_text(o.partition_hysteresis), "must be >= 0");
  require(o, system.supports_subsets(), "method", o.method,
          "the system cannot evaluate particle subsets (OdeSystem::supports_subsets)");
  require(o, system.num_roots() == 0, "method", o.method, "root finding is not supported with block steps");
  require(o, !o.communicator.distributed(), "method", o.method, "block steps are serial only");
}

}  // namespace

// ARKODE 6.4.1 enum order (arkode/arkode_butcher_erk.h); names accepted by ERKStepSetTableName.
std::vector<std::string> erk_table_names() {
  static const char* const kNames[] = {
      "ARKODE_HEUN_EULER_2_1_2",      "ARKODE_BOGACKI_SHAMPINE_4_2_3",
      "ARKODE_ARK324L2SA_ERK_4_2_3",  "ARKODE_ZONNEVELD_5_3_4",
      "ARKODE_ARK436L2SA_ERK_6_3_4",  "ARKODE_SAYFY_ABURUB_6_3_4",
      "ARKODE_CASH_KARP_6_4_5",       "ARKODE_FEHLBERG_6_4_5",
      "ARKODE_DORMAND_PRINCE_7_4_5",  "ARKODE_ARK548L2SA_ERK_8_4_5",
      "ARKODE_VERNER_8_5_6",          "ARKODE_FEHLBERG_13_7_8",
      "ARKODE_KNOTH_WOLKE_3_3",       "ARKODE_ARK437L2SA_ERK_7_3_4",
      "ARKODE_ARK548L2SAb_ERK_8_4_5",
  };
  static_assert(std::size(kNames) == ARKODE_MAX_ERK_NUM - ARKODE_MIN_ERK_NUM + 1);
  return {std::begin(kNames), std::end(kNames)};
}

bool erk_table_has_embedding(const std::string& name) {
  ARKodeButcherTable table = ARKodeButcherTable_LoadERKByName(name.c_str());
  if (table == nullptr) return false;
  const bool embedded = table->d != nullptr && table->p > 0;
  ARKodeButcherTable_Free(table);
  return embedded;
}

namespace detail {

std::unique_ptr<Stepper> make_validated_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                                const Real* y0) {
  validate_common(system, opts);
  if (opts.method == "leapfrog" || opts.method == "leapfrog-rev") {
    validate_leapfrog(system, opts, t0, y0);
    return make_leapfrog_stepper(system, opts, t0, y0);
  }
  if (opts.method == "leapfrog-blocks") {
    validate_blocks(system, opts);
    return make_block_leapfrog_stepper(system, opts, t0, y0);
  }
  if (opts.method.rfind("mri-", 0) == 0) {
    validate_mri(system, opts);
    return make_mri_stepper(system, opts, t0, y0);
  }
  if (opts.method == "ark-imex") {
    require(opts, system.has_stiff_diagonal(), "method", opts.method,
            "the system has no stiff diagonal part (use an ERK table)");
    require(opts, is_imex_pair(opts.imex_table), "imex_table", opts.imex_table,
            "unknown ARK pair (ARK324L2SA, ARK436L2SA, ARK437L2SA, ARK548L2SA, ARK548L2SAb)");
    return make_imex_stepper(system, opts, t0, y0);
  }
  require(opts, is_erk(opts.method), "method", opts.method,
          "not an ERK table of SUNDIALS 6.4.1, \"ark-imex\", \"leapfrog\", \"leapfrog-rev\", \"leapfrog-blocks\" or \"mri-<table>\"");
  require(opts, opts.fixed_dt > 0 || erk_table_has_embedding(opts.method), "method", opts.method,
          "table has no embedding: adaptive steps impossible, set fixed_dt");
  return make_erk_stepper(system, opts, t0, y0);
}

}  // namespace detail

// The guard checks each rank's own state; a distributed run agrees on its answers around it.
std::unique_ptr<Stepper> make_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                      const Real* y0) {
  auto guard = std::make_unique<GuardedSystem>(system);  // one guard per run
  guard->inject_nan_from(opts.inject_nan_from);
  auto inner = opts.communicator.distributed() ? detail::make_distributed_stepper(*guard, opts, t0, y0)
                                               : detail::make_validated_stepper(*guard, opts, t0, y0);
  const GuardedSystem* counter = guard.get();
  return std::make_unique<detail::WrapperOwningStepper>(std::move(guard), std::move(inner),
                                                        [counter] { return counter->particle_evals(); });
}

void Stepper::resize(const Resized&) {
  throw std::logic_error("this stepper cannot change the size of its state");
}

std::string describe(const StepperOptions& o) {
  std::ostringstream s;
  if (o.method == "leapfrog" || o.method == "leapfrog-rev") {
    s << (o.method == "leapfrog" ? "leapfrog KDK, " : "leapfrog-rev (KDK, q drifted with x by the midpoint rule), ");
    if (o.fixed_dt > 0) s << "fixed dt=" << o.fixed_dt;
    else s << "dt=" << o.cfl_safety << " x max_stable_dt";
    if (o.fixed_dt <= 0 && o.max_dt > 0) s << ", max_dt=" << o.max_dt;
    return s.str();
  }
  if (o.method == "leapfrog-blocks") {
    s << "leapfrog KDK with power-of-two block steps, top dt=" << (o.fixed_dt > 0 ? o.fixed_dt : o.max_dt)
      << ", levels from " << o.cfl_safety << " x particle_stable_dt, hysteresis " << o.partition_hysteresis
      << (o.fit_block_cycles ? ", cycles fitted" : "");
    return s.str();
  }
  if (o.method.rfind("mri-", 0) == 0) {
    s << "MRIStep " << o.method.substr(4);
    if (o.mri_levels > 2) s << ", " << o.mri_levels << " nested levels";
    if (o.fixed_dt > 0) {
      s << ", slow dt=" << o.fixed_dt << ", fast " << o.mri_fast_table << " dt=slow/" << o.mri_ratio;
      if (o.mri_levels > 2) s << '^' << o.mri_levels - 1;
    }
    else s << ", slow dt=max_dt/2^l (" << o.mri_slow_fraction << " of the particles slow), max_dt=" << o.max_dt
           << ", fast " << o.mri_fast_table << " dt=slow/max(" << o.mri_ratio << ", 2^levels)"
           << (o.mri_levels > 2 ? " per level" : "");
    s << ", levels from " << o.cfl_safety << " x particle_stable_dt, hysteresis " << o.partition_hysteresis
      << ", max_steps=" << o.max_steps;
    return s.str();
  }
  if (o.method == "ark-imex") s << "ARKStep IMEX " << o.imex_table;
  else s << "ERKStep " << o.method;
  if (o.fixed_dt > 0) {
    s << ", fixed dt=" << o.fixed_dt;
  } else {
    s << ", adaptive rtol=" << o.rtol << " atol=";
    if (o.atol.size() > 1) s << "per-entry (" << o.atol.size() << ")";
    else s << (o.atol.empty() ? 1e-9 : o.atol.front());
    if (o.max_dt > 0) s << " max_dt=" << o.max_dt;
    if (o.cap_by_stability) s << " dt<=" << o.cfl_safety << " x max_stable_dt";
    else s << " no stability cap";
  }
  s << ", max_steps=" << o.max_steps;
  return s.str();
}

std::string format_stats(const StepperStats& st) {
  std::ostringstream s;
  s << "steps=" << st.steps << " attempts=" << st.attempts << " rhs_evals=" << st.rhs_evals;
  if (st.rhs_evals_implicit > 0) s << " rhs_evals_implicit=" << st.rhs_evals_implicit;
  s << " err_test_fails=" << st.error_test_failures;
  if (st.rhs_evals_implicit > 0)
    s << " nonlin_fails=" << st.nonlinear_failures << " lin_solves=" << st.linear_solves;
  s << " rhs_recoveries=" << st.rhs_recoveries;
  if (st.corrector_iterations > 0) s << " corrector_iterations=" << st.corrector_iterations;
  s << " particle_evals=" << st.particle_evals;
  for (std::size_t l = 0; l < st.levels.size(); ++l)
    s << " level" << l << "=(steps=" << st.levels[l].steps << " rhs_evals=" << st.levels[l].rhs_evals
      << " particle_evals=" << st.levels[l].particle_evals << ")";
  s << " last_dt=" << st.last_dt
    << " t=" << st.current_time;
  return s.str();
}

}  // namespace sphark
