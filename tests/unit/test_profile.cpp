#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <thread>

#include "sphark/core/profile.hpp"

namespace sphark {
namespace {

TEST(RunProfile, ScopedPhaseAddsOnlyWhenEnabled) {
  RunProfile& p = run_profile();
  p.reset();
  p.enable(false);
  { ScopedPhase t(Phase::Forces); }
  EXPECT_EQ(p.calls(Phase::Forces), 0);
  EXPECT_EQ(p.seconds(Phase::Forces), 0.0);
  p.enable(true);
  {
    ScopedPhase t(Phase::Forces);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  EXPECT_EQ(p.calls(Phase::Forces), 1);
  EXPECT_GE(p.seconds(Phase::Forces), 0.002);
  p.enable(false);
  p.reset();
}

TEST(RunProfile, SummaryDerivesStepperAndOtherRhsWork) {
  RunProfile& p = run_profile();
  p.reset();
  p.add(Phase::Neighbours, 1.0);
  p.add(Phase::DensityH, 2.0);
  p.add(Phase::Forces, 3.0);
  p.add(Phase::Rhs, 7.0);      // 1 s of other RHS work
  p.add(Phase::Advance, 9.0);  // 2 s in the stepper itself
  p.add(Phase::Output, 0.5);
  std::ostringstream os;
  p.print(os, 10.0);
  // The line of each derived row, e.g. "  other rhs work   1.000 s   10.0 %   1 calls".
  auto row = [&](const std::string& name) {
    const std::string s = os.str();
    const auto at = s.find("  " + name + " ");
    if (at == std::string::npos) return std::string("missing: ") + name;
    return s.substr(at, s.find('\n', at) - at);
  };
  auto has = [](const std::string& line, const std::string& part) {
    return line.find(part) != std::string::npos;
  };
  EXPECT_TRUE(has(row("other rhs work"), " 1.000 s") && has(row("other rhs work"), " 10.0 %"))
      << row("other rhs work");
  const std::string stepper = row("stepper (ARKODE vector work etc.)");
  EXPECT_TRUE(has(stepper, " 2.000 s") && has(stepper, " 20.0 %")) << stepper;
  const std::string rest = row("set-up and rest");
  EXPECT_TRUE(has(rest, " 0.500 s") && has(rest, " 5.0 %")) << rest;
  p.reset();
}

}  // namespace
}  // namespace sphark
