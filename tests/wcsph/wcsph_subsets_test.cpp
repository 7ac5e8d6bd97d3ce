// The multirate interface of WcsphSystem (issue #17, src/schemes/wcsph/wcsph_subsets.cpp), on a
// disturbed periodic lattice with cleaning, viscosity and the corrected density diffusion on:
//  - rhs_subset(A) and rhs_subset(complement of A) are rhs() bit for bit on their own particles
//    and zero elsewhere (the density gradients the active rows read are computed for their
//    neighbours too: without them the diffusion term of a row at the set's edge differs);
//  - particle_stable_dt is each particle's own Courant / force step, and its minimum is at least
//    max_stable_dt (which combines the largest speed and the largest sound speed).
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "sphark/kernels/kernels.hpp"
#include "sphark/operators/tait_eos.hpp"
#include "sphark/schemes/wcsph/wcsph_system.hpp"
#include "../support/wcsph_lattice.hpp"

using namespace sphark;

namespace {
using K = WendlandC2<2>;
using Sys = WcsphSystem<2, K>;
constexpr int kSide = 30;
constexpr Real kRho0 = 1000, kC0 = 20;
const test::WcsphLattice kLattice{kSide, 0.05, kRho0, kC0, 9};

// the lattice's fluid with viscosity and cleaning on
WcsphParams<2> params() {
  WcsphParams<2> p = kLattice.params();
  p.alpha = 0.1;
  p.cleaning = true;
  p.clean_speed = 2 * kC0;
  return p;
}

Sys lattice_system() { return Sys(kLattice.particles(), params(), kLattice.box()); }
std::vector<Real> disturbed_state(const StateLayout& L) { return kLattice.disturbed_state(L); }
}  // namespace

TEST(WcsphSubsets, TwoComplementarySubsetsAreTheFullRhsBitForBit) {
  Sys sys = lattice_system();
  ASSERT_TRUE(sys.supports_subsets());
  const std::vector<Real> y = disturbed_state(sys.layout());
  const std::size_t n = sys.num_particles();
  std::vector<std::size_t> a_set, b_set;  // a block of rows (edges inside the box) and the rest
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t col = i % kSide, row = i / kSide;
    (col >= 5 && col < 12 && row >= 8 && row < 20 ? a_set : b_set).push_back(i);
  }
  std::vector<Real> full(y.size()), fa(y.size(), 7), fb(y.size(), 7);
  ASSERT_EQ(sys.rhs(0, y.data(), full.data()), 0);
  ASSERT_EQ(sys.rhs_subset(0, y.data(), a_set, fa.data()), 0);
  ASSERT_EQ(sys.rhs_subset(0, y.data(), b_set, fb.data()), 0);
  const std::vector<std::size_t> owner = sys.entry_particles();
  std::size_t nonzero = 0;
  for (std::size_t k = 0; k < y.size(); ++k) {
    const bool in_a = std::binary_search(a_set.begin(), a_set.end(), owner[k]);
    EXPECT_EQ(in_a ? fb[k] : fa[k], 0.0) << "entry " << k << " outside its set";
    EXPECT_EQ(in_a ? fa[k] : fb[k], full[k]) << "entry " << k << " (particle " << owner[k] << ")";
    nonzero += full[k] != 0;
  }
  EXPECT_GT(nonzero, y.size() * 3 / 4);
}

TEST(WcsphSubsets, ParticleStableStepsAreEachParticlesOwn) {
  Sys sys = lattice_system();
  std::vector<Real> y = disturbed_state(sys.layout());
  const StateLayout& L = sys.layout();
  auto v = vector_field<2>(y.data(), L, Field::Velocity);
  v.col(17) *= 300;  // one fast particle: its Courant step the shortest
  std::vector<Real> f(y.size()), dt(sys.num_particles());
  ASSERT_EQ(sys.rhs(0, y.data(), f.data()), 0);
  ASSERT_EQ(sys.particle_stable_dt(0, y.data(), f.data(), dt.data()), 0);
  const WcsphParams<2> p = params();
  const auto dv = vector_field<2>(f.data(), L, Field::Velocity);
  const auto rho = scalar_field(y.data(), L, Field::Density);
  for (std::size_t a = 0; a < sys.num_particles(); ++a) {
    const Real c = std::max(p.cleaning_speed(), tait_sound_speed(rho[a], kRho0, kC0));
    Real expected = p.cfl * p.h / (c + v.col(a).norm() + 1.2 * p.alpha * c);
    expected = std::min(expected, p.cfl * std::sqrt(p.h / dv.col(a).norm()));
    EXPECT_DOUBLE_EQ(dt[a], expected) << a;
  }
  EXPECT_EQ(std::min_element(dt.begin(), dt.end()) - dt.begin(), 17);
  EXPECT_GE(*std::min_element(dt.begin(), dt.end()), sys.max_stable_dt(0, y.data(), f.data()));
  EXPECT_GT(*std::max_element(dt.begin(), dt.end()), 3 * dt[17]);
}
