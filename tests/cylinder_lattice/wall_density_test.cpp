// Ghost layer of a relaxed particle set around the obstacle: the density of the particles at
// the wall (eq. 1 summed over real + ghost particles) equals the interior density within 2%.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "lattice_helpers.hpp"
#include "sphark/boundaries/wall_relaxation.hpp"

namespace sphark {
namespace {

struct WallDensity {
  Real wall = 0, interior = 0;
};

// Relaxes n random particles against ghosts of `relax_map`, then evaluates the densities with
// ghosts of `map`.
WallDensity wall_density(GhostMap relax_map, GhostMap map, std::size_t n) {
  const LatticeParams p = lattice_params(lattice_test::undriven(map), n);
  std::vector<Real> x = random_fluid_positions(p, n, 7, 0.7);
  const PeriodicBox<2> box = lattice_box(p);
  RelaxOptions ro;
  ro.h_over_dx = p.eta;
  ro.max_iterations = 400;
  ro.tolerance = 2e-3;
  const Wall<2> wall = Cylinder<2>{Vec<2>::Zero(), p.radius, FluidSide::Outside};
  relax_near_wall<2>(x, wall, relax_map, p.h_ref, std::vector<char>(n, 1), box, ro);

  LatticeSystem sys(n, p);
  const std::vector<Real> y = lattice_test::state(sys, x, Vec<2>::Zero());
  EXPECT_EQ(sys.prepare(y.data()), 0) << sys.last_error();
  EXPECT_GT(sys.ghost_count(), 0u);
  WallDensity d;
  int nw = 0, ni = 0;
  for (std::size_t a = 0; a < n; ++a) {
    const Real s = std::hypot(x[2 * a], x[2 * a + 1]) - p.radius;
    if (s < p.h_ref) d.wall += sys.density()[a], ++nw;                 // within h of the wall
    else if (s > 2 * 2 * p.h_ref) d.interior += sys.density()[a], ++ni;  // beyond two supports
  }
  EXPECT_GT(nw, 10);
  EXPECT_GT(ni, 100);
  d.wall /= nw;
  d.interior /= ni;
  return d;
}

TEST(LatticeWallDensity, RelaxedSetGivesInteriorDensityAtTheWall) {
  constexpr std::size_t n = 1200;  // support 2h = 0.076 < (sqrt 2 - 1) R: Psi covers the layer
  for (GhostMap map : {GhostMap::DensityPreserving, GhostMap::Mirror}) {
    const WallDensity d = wall_density(map, map, n);
    const Real dev = d.wall / d.interior - 1;
    std::printf("[ %s ghosts, relaxed with them ] wall %.5f interior %.5f deviation %+.3f%%\n", map_name(map).c_str(),
                d.wall, d.interior, 100 * dev);
    EXPECT_LT(std::abs(dev), 0.02) << map_name(map);
  }
}

}  // namespace
}  // namespace sphark
