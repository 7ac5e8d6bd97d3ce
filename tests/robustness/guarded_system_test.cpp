// Blow-up handling: a non-finite right-hand side is a recoverable failure (the stepper retries
// with smaller steps), a persistent one ends the run cleanly at the last good state, and the
// report names the particles.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sphark/integrate/stepper.hpp"
#include "sphark/integrate/guarded_system.hpp"

using namespace sphark;

namespace {
// n independent unit oscillators x'' = -x (x = cos t, v = -sin t), constant density.
class Oscillators final : public OdeSystem {
 public:
  explicit Oscillators(std::size_t n) : L(n) { L.add(Field::Position, 1).add(Field::Velocity, 1).add(Field::Density, 1); }
  std::size_t size() const override { return L.size(); }
  const StateLayout* state_layout() const override { return &L; }
  int rhs(Real, const Real* y, Real* ydot) override {
    const std::size_t n = L.particles();
    for (std::size_t i = 0; i < n; ++i) {
      ydot[i] = y[n + i];
      ydot[n + i] = -y[i];
      if (i % 2 == 1) ydot[n + i] += nan_force;
      ydot[2 * n + i] = 0;
    }
    return 0;
  }
  std::size_t position_offset() const override { return 0; }
  std::size_t velocity_offset() const override { return L.particles(); }
  std::size_t position_size() const override { return L.particles(); }
  std::vector<Real> initial() const {
    std::vector<Real> y(L.size(), 0);
    for (std::size_t i = 0; i < L.particles(); ++i) y[i] = 1, y[2 * L.particles() + i] = 1000;
    return y;
  }
  StateLayout L;
  Real nan_force = 0;
};

struct Failure {
  AdvanceStatus status;
  Real t;
  std::vector<Real> y;
  StepperStats stats;
  std::string reason;
};

Failure run_with_injection(const std::string& method, Real fixed_dt, Real inject_at) {
  Oscillators osc(4);
  StepperOptions o;
  o.inject_nan_from = inject_at;
  o.method = method;
  o.rtol = 1e-10;
  o.atol = {1e-12};
  o.fixed_dt = fixed_dt;
  o.min_dt = 1e-9;
  std::vector<Real> y = osc.initial();
  auto stepper = make_stepper(osc, o, 0.0, y.data());  // the stepper guards the system
  Failure f;
  f.status = stepper->advance(1.0, y.data(), f.t);
  f.y = y;
  f.stats = stepper->stats();
  f.reason = stepper->failure_reason();
  return f;
}
}  // namespace

TEST(GuardedSystem, InjectedNanIsRetriedThenFailsAtTheLastGoodState) {
  for (const auto& [method, dt] : {std::pair<std::string, Real>{"ARKODE_DORMAND_PRINCE_7_4_5", 0.0},
                                   {"ARKODE_DORMAND_PRINCE_7_4_5", 0.01}, {"leapfrog", 0.01}}) {
    SCOPED_TRACE(method + (dt > 0 ? " fixed" : " adaptive"));
    const Failure f = run_with_injection(method, dt, 0.5);
    ASSERT_EQ(f.status, AdvanceStatus::Failed);
    EXPECT_GT(f.stats.rhs_recoveries, 0);  // retried with smaller steps first
    EXPECT_LT(f.t, 0.5);                   // the last good state is before the fault
    EXPECT_GT(f.t, 0.5 - (dt > 0 ? dt : 0.1));
    EXPECT_LT(f.stats.attempts, 2000);     // ended by min_dt / the retry limit, not max_steps
    EXPECT_NE(f.reason.find("velocity of particle 0"), std::string::npos) << f.reason;
    // a genuine state of the method: finite and on the exact solution to the method's accuracy
    const Real tol = dt > 0 ? (method == "leapfrog" ? 1e-4 : 1e-9) : 1e-8;
    for (std::size_t i = 0; i < 4; ++i) {
      EXPECT_NEAR(f.y[i], std::cos(f.t), tol);
      EXPECT_NEAR(f.y[4 + i], -std::sin(f.t), tol);
      EXPECT_EQ(f.y[8 + i], 1000);
    }
  }
}

TEST(GuardedSystem, NamesNonFiniteDerivativesAndNonPhysicalStates) {
  Oscillators osc(12);
  GuardedSystem sys(osc);
  std::vector<Real> y = osc.initial(), ydot(y.size());
  EXPECT_EQ(sys.rhs(0, y.data(), ydot.data()), 0);
  osc.nan_force = std::numeric_limits<Real>::infinity();  // odd particles: 6 of them
  EXPECT_EQ(sys.rhs(0, y.data(), ydot.data()), 1);
  EXPECT_NE(sys.last_error().find("velocity of particles 1, 3, 5, 7, 9 (+1 more)"), std::string::npos)
      << sys.last_error();
  osc.nan_force = 0;
  y[2 * 12 + 4] = -1;  // negative density of particle 4
  y[3] = std::numeric_limits<Real>::quiet_NaN();  // position of particle 3
  EXPECT_EQ(sys.rhs(0, y.data(), ydot.data()), 1);
  EXPECT_NE(sys.last_error().find("position of particle 3; density of particle 4"), std::string::npos)
      << sys.last_error();
  EXPECT_EQ(sys.guarded_failures(), 2);
}

TEST(GuardedSystem, NegativeInternalEnergyAndNonPositiveDensityAreNonPhysical) {
  StateLayout L(3);
  L.add(Field::Position, 2).add(Field::Density, 1).add(Field::InternalEnergy, 1);
  std::vector<Real> y(L.size(), 1.0);
  EXPECT_TRUE(nonphysical_entries(L, y.data()).empty());
  y[L.offset(Field::InternalEnergy) + 0] = 0;      // u = 0: allowed (cold gas)
  y[L.offset(Field::InternalEnergy) + 2] = -1e-300;  // u < 0: not
  y[L.offset(Field::Density) + 1] = 0;             // rho = 0: not
  const std::vector<std::size_t> bad = nonphysical_entries(L, y.data());
  EXPECT_EQ(bad, (std::vector<std::size_t>{L.offset(Field::Density) + 1, L.offset(Field::InternalEnergy) + 2}));
  EXPECT_EQ(describe_entries(L, bad), "density of particle 1; internal_energy of particle 2");
}
