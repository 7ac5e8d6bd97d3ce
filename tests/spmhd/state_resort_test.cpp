// Re-sorting an Orszag-Tang state into cell order (run/state_resort.hpp): the lattice's row-by-row
// numbering is scrambled by the measure (3/16 of a square lattice; the hexagonal one likewise),
// the re-sorted state holds every particle's entries, moved together (the entry map says where
// from), is in cell order, and its right-hand side is the old one moved along, to round-off (the
// rows sum in the new particle order).
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "sphark/run/state_resort.hpp"
#include "sphark/scenes/orszag_tang/orszag_tang.hpp"

namespace sphark {
namespace {

OrszagTangParams small() {
  OrszagTangParams p;
  p.nx = 32;
  return p;
}

TEST(StateResort, OrszagTangLatticeIsResortedIntoCellOrderWithItsDerivatives) {
  OrszagTang ot("cleaning", small());
  const StateLayout layout = ot.scheme.layout();
  std::vector<Real> before(layout.size());
  ASSERT_EQ(ot.scheme.rhs(0, ot.y0.data(), before.data()), 0) << ot.scheme.last_error();
  const std::optional<PeriodicBox<2>> box = unit_periodic_box();
  const StateResortOptions o{0.1, 4.0 / ot.nx};
  const std::size_t n = layout.particles(Species::Gas);
  const Real* x0 = ot.y0.data() + layout.offset(Field::Position);
  const Real scrambled = scrambled_fraction<2>(x0, n, o.cell, box);
  EXPECT_GT(scrambled, 0.1);
  const std::optional<TimeLoopHooks::Resize> r = resort_if_scrambled<2>(ot.scheme, layout, ot.y0.data(), o, box);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->y.size(), ot.y0.size());
  ASSERT_EQ(r->entry_source.size(), ot.y0.size());
  for (std::size_t k = 0; k < r->y.size(); ++k) ASSERT_EQ(r->y[k], ot.y0[r->entry_source[k]]) << k;
  // a permutation of the particles: every field of one particle from the same old particle
  const std::size_t x_at = layout.offset(Field::Position), v_at = layout.offset(Field::Velocity);
  const std::size_t psi_at = layout.offset(Field::Psi);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t from = (r->entry_source[x_at + 2 * i] - x_at) / 2;
    ASSERT_EQ(r->entry_source[v_at + 2 * i + 1], v_at + 2 * from + 1) << i;
    ASSERT_EQ(r->entry_source[psi_at + i], psi_at + from) << i;
  }
  EXPECT_EQ(scrambled_fraction<2>(r->y.data() + x_at, n, o.cell, box), 0.0);
  EXPECT_FALSE(resort_if_scrambled<2>(ot.scheme, layout, r->y.data(), o, box));  // once only
  std::vector<Real> after(layout.size());
  ASSERT_EQ(ot.scheme.rhs(0, r->y.data(), after.data()), 0) << ot.scheme.last_error();
  Real scale = 0;
  for (const Real d : before) scale = std::max(scale, std::abs(d));
  for (std::size_t k = 0; k < after.size(); ++k)
    ASSERT_NEAR(after[k], before[r->entry_source[k]], 1e-12 * scale) << k;
  EXPECT_FALSE(resort_if_scrambled<2>(ot.scheme, layout, ot.y0.data(), StateResortOptions{0, o.cell}, box));  // off
}

}  // namespace
}  // namespace sphark
