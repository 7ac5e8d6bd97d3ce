#pragma once
// The "leapfrog-blocks" stepper's class (src/integrate/block_leapfrog_stepper.cpp: the scheme;
// block_leapfrog_levels.cpp: stable steps, levels, each cycle's top step;
// block_leapfrog_removal.cpp: particles removed inside a top step). Private to src/integrate.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>

#include "sphark/core/profile.hpp"
#include "sphark/integrate/callback_errors.hpp"
#include "sphark/integrate/level_partition.hpp"
#include "steppers.hpp"

namespace sphark::detail {

constexpr int kMaxLevel = 30;  // at most 2^30 substeps per top step
constexpr int kMaxBlockCorrectorIterations = 30;  // Phantom's maxits
constexpr std::int64_t kTicks = std::int64_t(1) << kMaxLevel;

struct CycleFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct CycleInterrupted {};  // StepperOptions::interrupt said so

class BlockLeapfrogStepper final : public Stepper {
 public:
  BlockLeapfrogStepper(OdeSystem& system, const StepperOptions& opts, Real t0, const Real* y0);
  AdvanceStatus advance(Real t_out, Real* y, Real& t) override;
  AdvanceStatus step(Real t_out, Real* y, Real& t) override;
  StepperStats stats() const override;
  std::string failure_reason() const override { return failure_; }
  std::vector<int> roots_found() const override { return {}; }
  // The derivative of the next kicks (FSAL), each particle's level, and whether the next cycle
  // bins afresh: a restart at (t, y) with them takes this run's steps bit for bit.
  std::vector<Real> resume_data() const override;
  // Between cycles (all particles synchronised): the new state at t_; the next kicks use
  // `carried` (the derivative moved with its entries) or the RHS at the new state; every particle
  // is binned afresh at the next cycle.
  void resize(const Resized& state) override;
  std::vector<Real> carried_data() const override { return failed_ ? std::vector<Real>{} : dy_; }

 private:
  void index_entries();
  std::int64_t length(int level) const { return kTicks >> level; }
  void cycle(Real t_out);  // one top step towards t_out (next_top), t_ set to its end
  struct Top {
    Real dt, t_end;
  };
  Top next_top(Real t_out) const;
  void update_stable_steps(Real t, const std::vector<std::size_t>& particles);
  void assign_levels(Real t, const std::vector<std::size_t>& particles, std::int64_t tick, bool fresh);
  void kick(const std::vector<std::size_t>& particles, Real half_step_factor, std::vector<Real>& w) const;
  std::vector<std::size_t> ending_at(std::int64_t tick) const;
  void predict(std::int64_t tick);
  std::vector<std::size_t> woken_at(std::int64_t tick) const;
  void cut_back(const std::vector<std::size_t>& woken, std::int64_t tick);
  void evaluate(Real t, const std::vector<std::size_t>& active);
  void end_kicks(const std::vector<std::size_t>& ending, const std::vector<std::size_t>& woken, std::int64_t tick);
  void correct(Real t, const std::vector<std::size_t>& active, const std::vector<std::size_t>& ending,
               const std::vector<std::size_t>& woken, std::int64_t tick);
  Real predictor_difference(const std::vector<std::size_t>& active) const;
  void count(const std::vector<std::size_t>& active);
  void reindex();
  void remove(Real t, std::vector<std::size_t>& active);
  void take(Real t, StepperOptions::Removal& r, std::vector<std::size_t>& active);

  OdeSystem& system_;
  const StepperOptions opts_;
  const Real top_;  // the top step: fixed_dt, else max_dt
  std::size_t n_, np_, xp_, vp_;
  std::vector<std::size_t> owner_;                 // entry -> particle
  std::vector<std::vector<std::size_t>> entries_;  // particle -> its kicked entries (not x)
  Real t_;
  std::vector<Real> y_, dy_;  // synchronised state at t_ and its derivative (FSAL)
  std::vector<Real> w_, eval_, out_, bound_;
  std::vector<Real> pre_;     // the active entries before their end kicks
  std::vector<Real> stable_;  // each particle's step since its last rebin
  std::vector<Real> lead_;    // predict: each particle's time from the middle of its step
  std::vector<int> level_;
  std::vector<std::int64_t> start_;  // tick at which each particle's current step began
  LevelPartition bins_;
  Real tick_dt_ = 0;
  bool fresh_ = true;  // the next cycle bins afresh (first cycle, or a new top step)
  std::vector<LevelStats> level_stats_;
  long events_ = 0, rhs_evals_ = 1, wakeups_ = 0, corrector_iterations_ = 0;
  bool removed_ = false;  // particles removed inside the current cycle (remove_active)
  std::vector<std::size_t> wake_next_;  // ascending: to be woken at the next event (wake_next)
  Real last_dt_ = 0;
  bool failed_ = false;
  std::string failure_;
};

}  // namespace sphark::detail
