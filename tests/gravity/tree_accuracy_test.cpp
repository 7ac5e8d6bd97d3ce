// Tree against direct summation (the acceptance figures): median and 99th-percentile
// relative force error at theta = 0.3, 0.5, 0.7 on 4000 particles, for a uniform sphere and a
// centrally concentrated rho ~ 1/r sphere (h from the exact density); the potential energy.
#include <gtest/gtest.h>

#include <cstdio>

#include "gravity_test_support.hpp"
#include "sphark/gravity/sphere_particles.hpp"

using namespace sphark;
using namespace sphark::gravity_test;

namespace {

struct ErrorRow {
  Real theta, median, p99, energy;
};

std::vector<ErrorRow> tree_errors(const SphereParticles& p, const char* name) {
  const Field direct = solve(GravitySolver::Direct, p.sources());
  std::vector<ErrorRow> rows;
  for (Real theta : {0.3, 0.5, 0.7}) {
    GravityOptions opt;
    opt.theta = theta;
    const Field tree = solve(GravitySolver::Tree, p.sources(), opt);
    const std::vector<Real> e = relative_force_errors(tree, direct);
    rows.push_back({theta, quantile(e, 0.5), quantile(e, 0.99), std::abs(tree.energy / direct.energy - 1)});
    std::printf("%-10s theta %.1f  median %.3e  p99 %.3e  |dE/E| %.3e\n", name, theta, rows.back().median,
                rows.back().p99, rows.back().energy);
  }
  return rows;
}

void expect_accurate_and_growing_with_theta(const std::vector<ErrorRow>& rows) {
  EXPECT_LE(rows[1].median, 1e-3);  // the acceptance at theta = 0.5
  for (std::size_t k = 1; k < rows.size(); ++k) {
    EXPECT_GT(rows[k].median, rows[k - 1].median);
    EXPECT_GT(rows[k].p99, rows[k - 1].p99);
  }
}

}  // namespace

TEST(TreeAccuracy, UniformSphere) {
  const SphereParticles p = random_sphere(SphereProfile::Uniform, 4000, 1, 1, 1.2, 11);
  expect_accurate_and_growing_with_theta(tree_errors(p, "uniform"));
}

TEST(TreeAccuracy, InverseRSphere) {
  const SphereParticles p = random_sphere(SphereProfile::InverseR, 4000, 1, 1, 1.2, 12);
  expect_accurate_and_growing_with_theta(tree_errors(p, "1/r"));
}
