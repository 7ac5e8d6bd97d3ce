// The exact elliptic-drop solution: area a b = R^2 conserved (incompressibility), fourth-order
// convergence of its RK4 integration, and the small-amplitude limit (an n = 2 surface mode in a
// harmonic trap oscillates with the frequency sqrt(2) omega).
#include <gtest/gtest.h>

#include <cmath>

#include "sphark/analytic/elliptic_drop.hpp"

using namespace sphark;

TEST(EllipticDrop, ConservesArea) {
  EllipticDrop drop(1.0, 100.0, 100.0);
  for (Real t : {0.005, 0.012, 0.05, 0.1}) {
    const auto s = drop.at(t);
    EXPECT_NEAR(s.a * s.b, 1.0, 1e-12) << t;
  }
}

TEST(EllipticDrop, Rk4IsFourthOrder) {
  EllipticDrop drop(1.0, 100.0, 100.0);
  const Real ref = drop.at(0.02, 1e-7).a;
  const Real e1 = std::abs(drop.at(0.02, 4e-4).a - ref);
  const Real e2 = std::abs(drop.at(0.02, 2e-4).a - ref);
  EXPECT_NEAR(std::log2(e1 / e2), 4.0, 0.2);
}

TEST(EllipticDrop, SmallAmplitudeFrequencyIsSqrt2Omega) {
  // Linearise: a = 1 + eps, A ~ -d eps/dt, d2 eps/dt2 = -(omega^2)(a^2-b^2)/(a^2+b^2) ~ -2 omega^2 eps.
  const Real omega = 10.0, amp = 1e-4;
  EllipticDrop drop(1.0, amp, omega);
  const Real period = 2 * kPi / (std::sqrt(2.0) * omega);
  const auto half = drop.at(0.5 * period, 1e-5);
  const auto full = drop.at(period, 1e-5);
  EXPECT_NEAR(half.A / amp, -1.0, 1e-3);  // velocity amplitude reversed after half a period
  EXPECT_NEAR(full.A / amp, 1.0, 1e-3);
  EXPECT_NEAR(full.a, 1.0, 1e-8);
}

// at(t) is a function of t alone: the kept grid state (later times continue from it) changes
// no bit of any answer, whatever was asked before, forwards, backwards or with another step.
TEST(EllipticDrop, TheAnswerDoesNotDependOnWhatWasAskedBefore) {
  const EllipticDrop walked(1.0, 100.0, 100.0);
  for (const Real t : {0.0, 1e-4, 2.5e-3, 2.5e-3, 0.0121, 0.05, 0.03, 0.1, 7e-6}) {
    const EllipticDropState s = walked.at(t), fresh = EllipticDrop(1.0, 100.0, 100.0).at(t);
    EXPECT_EQ(s.a, fresh.a) << t;
    EXPECT_EQ(s.b, fresh.b) << t;
    EXPECT_EQ(s.A, fresh.A) << t;
    walked.at(0.02, 4e-4);  // another grid in between
  }
}
