// LevelPartition: power-of-two levels of the particles' stable steps, with hysteresis.
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "sphark/integrate/level_partition.hpp"

namespace sphark {
namespace {

TEST(LevelPartition, LevelIsTheSmallestPowerOfTwoStepBelowTheStableStep) {
  const LevelPartition p(1.0, 10, 0.25);
  EXPECT_EQ(p.needed_level(1.0), 0);  // bin edges exact: dt_top / 2^l <= dt
  EXPECT_EQ(p.needed_level(0.5), 1);
  EXPECT_EQ(p.needed_level(std::nextafter(0.5, 0.0)), 2);
  EXPECT_EQ(p.needed_level(0.1), 4);  // 1/16 <= 0.1 < 1/8
  EXPECT_EQ(p.needed_level(5.0), 0);
  EXPECT_EQ(p.needed_level(std::numeric_limits<Real>::infinity()), 0);
  EXPECT_EQ(p.needed_level(1e-9), 10);  // clamped at max_level
  EXPECT_EQ(p.level_dt(3), 0.125);
}

TEST(LevelPartition, DeeperAtOnceShallowerOnlyWithTheHysteresisMargin) {
  LevelPartition p(1.0, 10, 0.25);
  const Real first[] = {0.2, 0.7, 2.0};
  EXPECT_TRUE(p.update(first));
  EXPECT_EQ(p.levels(), (std::vector<int>{3, 1, 0}));
  EXPECT_EQ(p.deepest(), 3);
  // 0.26 would fit level 2 (0.25) but not with the margin (0.26 / 1.25 < 0.25): stays at 3.
  const Real second[] = {0.26, 0.7, 2.0};
  EXPECT_FALSE(p.update(second));
  EXPECT_EQ(p.level(0), 3);
  // 0.32 / 1.25 = 0.256 >= 0.25: up to level 2, not further (needs 0.5 x 1.25 for level 1).
  const Real third[] = {0.32, 0.7, 2.0};
  EXPECT_TRUE(p.update(third));
  EXPECT_EQ(p.level(0), 2);
  // A shorter stable step moves a particle deeper at once, without margin.
  const Real fourth[] = {0.32, 0.49, 2.0};
  EXPECT_TRUE(p.update(fourth));
  EXPECT_EQ(p.level(1), 2);
  EXPECT_EQ(p.at(2), (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(p.at_least(1), (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(p.below(1), (std::vector<std::size_t>{2}));
}

TEST(LevelPartition, ANewParticleCountStartsAfresh) {
  LevelPartition p(1.0, 4, 10.0);
  const Real a[] = {0.2, 0.2};
  p.update(a);
  const Real b[] = {0.9, 0.9, 0.9};  // with hysteresis 10 they would have stayed at level 3
  EXPECT_TRUE(p.update(b));
  EXPECT_EQ(p.levels(), (std::vector<int>{1, 1, 1}));
}

TEST(LevelPartition, BadArgumentsAreOneLineErrors) {
  EXPECT_THROW(LevelPartition(0.0, 3, 0.25), std::invalid_argument);
  EXPECT_THROW(LevelPartition(1.0, -1, 0.25), std::invalid_argument);
  EXPECT_THROW(LevelPartition(1.0, 3, -0.1), std::invalid_argument);
  LevelPartition p(1.0, 3, 0.25);
  const Real bad[] = {0.5, std::numeric_limits<Real>::quiet_NaN()};
  EXPECT_THROW(p.update(bad), std::invalid_argument);
  EXPECT_THROW(p.needed_level(0.0), std::invalid_argument);
}

}  // namespace
}  // namespace sphark
