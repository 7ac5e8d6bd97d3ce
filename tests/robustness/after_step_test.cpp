// The time loop's after_step hook (run/time_loop.hpp): a system whose particle count changes
// between steps — here independent unit oscillators x'' = -x, one of them removed at t = 0.5 —
// continues through Stepper::resize. The survivors end where an uninterrupted run ends: bit for
// bit with the fixed-step leapfrog, within the tolerance with adaptive Dormand-Prince. The
// leapfrog's next kick uses the derivatives moved with their entries when the hook names every
// new entry's source (no evaluation: the oscillators' forces are their own, the same values), and
// is evaluated afresh at the resized state when it names none or an entry has none (a new
// particle). The adaptive leapfrog takes each step's max_stable_dt right after the step before
// (before after_step): kept across a resize that carries the derivatives, taken again after any
// other. The checkpoint written at the end carries the new particle count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "sphark/run/time_loop.hpp"
#include "../support/temp_dir.hpp"

using namespace sphark;
using sphark::test::TempDir;

namespace {
class Oscillators final : public OdeSystem {
 public:
  explicit Oscillators(std::size_t n) : layout_(layout_for(n)) {
    for (std::size_t i = 0; i < n; ++i) omega2_.push_back(1.0 + 0.1 * static_cast<Real>(i));  // frequencies differ
  }
  static StateLayout layout_for(std::size_t n) {
    StateLayout L(n);
    L.add(Field::Position, 1).add(Field::Velocity, 1);
    return L;
  }
  void keep(const std::vector<std::size_t>& kept) {  // the particles kept[i] become i
    std::vector<Real> w;
    for (std::size_t i : kept) w.push_back(omega2_[i]);
    omega2_ = w;
    layout_ = layout_for(kept.size());
  }
  const StateLayout& layout() const { return layout_; }
  std::size_t size() const override { return layout_.size(); }
  const StateLayout* state_layout() const override { return &layout_; }
  int rhs(Real, const Real* y, Real* ydot) override {
    const std::size_t n = layout_.particles();
    for (std::size_t i = 0; i < n; ++i) {
      ydot[i] = y[n + i];
      ydot[n + i] = -omega2_[i] * y[i];
    }
    return 0;
  }
  // 0.05 / the largest frequency (the removed particle 0 has the smallest: the same before and after)
  Real max_stable_dt(Real, const Real*, const Real*) override {
    ++stable_dt_calls;
    return 0.05 / std::sqrt(*std::max_element(omega2_.begin(), omega2_.end()));
  }
  long stable_dt_calls = 0;
  std::size_t position_offset() const override { return 0; }
  std::size_t velocity_offset() const override { return layout_.particles(); }
  std::size_t position_size() const override { return layout_.particles(); }

 private:
  StateLayout layout_;
  std::vector<Real> omega2_;
};

struct Outcome {
  std::vector<Real> y;
  std::size_t particles;
  std::size_t checkpoint_particles;
  long rhs_evals;
  long stable_dt_calls;
};

// How the hook hands over the state without particle 0: without entry sources, with them, or
// with them but one entry marked as new.
enum class Removal { none, afresh, with_sources, with_a_new_entry };

Outcome run(const std::string& method, Removal removal, const std::filesystem::path& dir) {
  Oscillators sys(4);
  std::vector<Real> y0(sys.size(), 0);
  for (std::size_t i = 0; i < 4; ++i) y0[i] = 1.0 + 0.25 * static_cast<Real>(i);
  StepperOptions o;
  o.method = method == "leapfrog adaptive" ? "leapfrog" : method;
  o.rtol = 1e-9;
  o.atol = {1e-12};
  if (method == "leapfrog") o.fixed_dt = 1.0 / 64;
  TimeLoopSettings s;
  s.program = "after_step_test";
  s.t_end = 2;
  s.sample_every = 0.25;
  s.diagnostics_csv = dir / "d.csv";
  s.columns = {"t"};
  s.checkpoint = dir / "c.bin";
  s.checkpoint_every = 2;
  s.quiet = true;
  TimeLoopHooks h;
  h.diagnostics = [](Real t, const Real*, const StepperStats&) { return std::vector<Real>{t}; };
  bool removed = false;
  if (removal != Removal::none)
    h.after_step = [&](Real t, const Real* y, const TimeLoopHooks::CarriedData&) -> std::optional<TimeLoopHooks::Resize> {
      if (removed || t < 0.5) return std::nullopt;
      removed = true;
      const StateLayout from = sys.layout(), to = from.with_count(Species::Gas, 3);
      std::vector<Real> next = resize_species(from, y, to, Species::Gas, {1, 2, 3});  // particle 0 leaves
      std::vector<std::size_t> sources;
      if (removal != Removal::afresh) sources = entry_sources(from, to, Species::Gas, {1, 2, 3});
      if (removal == Removal::with_a_new_entry) sources[1] = kNoEntrySource;
      sys.keep({1, 2, 3});
      return TimeLoopHooks::Resize{to, std::move(next), {}, std::move(sources), {}};
    };
  const TimeLoopResult r = run_time_loop(sys, sys.layout(), o, y0, s, h);
  EXPECT_TRUE(r.ok()) << r.failure;
  const std::size_t n = sys.layout().particles();
  std::vector<Real> survivors;  // x then v of the particles 1, 2, 3 of the original numbering
  const std::vector<Real> y = load_checkpoint(dir / "c.bin").y;
  const std::size_t skip = n == 4 ? 1 : 0;
  for (std::size_t i = skip; i < n; ++i) survivors.push_back(y[i]);
  for (std::size_t i = skip; i < n; ++i) survivors.push_back(y[n + i]);
  return {survivors, n, load_checkpoint(dir / "c.bin").particles(), r.stats.rhs_evals, sys.stable_dt_calls};
}
}  // namespace

TEST(AfterStep, ARunThatLosesAParticleContinuesAsAnUninterruptedOne) {
  for (const std::string method : {"leapfrog", "leapfrog adaptive", "ARKODE_DORMAND_PRINCE_7_4_5"}) {
    SCOPED_TRACE(method);
    TempDir a;
    const Outcome whole = run(method, Removal::none, a.path());
    for (const Removal removal : {Removal::afresh, Removal::with_sources, Removal::with_a_new_entry}) {
      SCOPED_TRACE(static_cast<int>(removal));
      TempDir b;
      const Outcome cut = run(method, removal, b.path());
      EXPECT_EQ(cut.particles, 3u);
      EXPECT_EQ(cut.checkpoint_particles, 3u);  // the checkpoint carries the new count
      ASSERT_EQ(whole.y.size(), cut.y.size());
      if (method != "ARKODE_DORMAND_PRINCE_7_4_5") {
        EXPECT_EQ(std::memcmp(whole.y.data(), cut.y.data(), whole.y.size() * sizeof(Real)), 0);
        // one evaluation per step, one more to start, one more after a removal unless every
        // entry's derivative moved with it; so too the adaptive one's stable steps
        const long again = removal == Removal::with_sources ? 0 : 1;
        EXPECT_EQ(cut.rhs_evals, whole.rhs_evals + again);
        if (method == "leapfrog adaptive") {
          EXPECT_EQ(cut.stable_dt_calls, whole.stable_dt_calls + again);
        }
      } else {
        for (std::size_t k = 0; k < whole.y.size(); ++k) EXPECT_NEAR(cut.y[k], whole.y[k], 1e-7);
      }
    }
  }
}
