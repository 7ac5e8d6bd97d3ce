// Static node-density test (seed 004, §7) on small relaxed sets at the paper's resolution
// (the resolution of 50 000 particles in the full geometry, h = 1.3 dx, Wendland C4, H = 2h):
// the mean node density of the ghosts within one kernel radius H of the wall must be within 1%
// of the inner value for the density-preserving map Psi. The mirror's deviation is reported
// beside it. The sets are relaxed in two stages (relaxed_set): a periodic glass, cut by the wall,
// then relaxed near the wall with Psi ghosts in the loop (the paper's ALARIC step). Relaxation
// boxes hold the part of each geometry that the evaluated ghosts see; particles near the boxes'
// non-periodic faces stay fixed (full-size runs: examples/ghost_static).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "sphark/boundaries/static_profile.hpp"

using namespace sphark;

namespace {

struct Window {
  const char* name;
  Wall<3> wall;
  PeriodicBox<3> relax_box;                      // fully periodic relaxation domain
  std::optional<PeriodicBox<3>> eval_box;        // periodic axes that are physical (cylinder axis)
  std::function<bool(const Vec<3>&)> evaluated;  // ghosts whose neighbourhood lies in the window
  std::function<bool(const Vec<3>&)> may_move;   // away from the window's non-periodic faces
  Real full_volume;                              // volume of the full geometry (paper: 50 000 in it)
};

PeriodicBox<3> box(Vec<3> lo, Vec<3> hi) {
  PeriodicBox<3> b;
  b.lo = lo;
  b.hi = hi;
  b.periodic = {true, true, true};
  return b;
}

struct Deviations {
  Real psi = 0, mirror = 0;
  std::size_t ghosts = 0;
};

Deviations run(const Window& w) {
  const Real dx = std::cbrt(w.full_volume / 50000.0);
  const std::size_t n = static_cast<std::size_t>(std::lround(w.relax_box.length().prod() / (dx * dx * dx)));
  RelaxOptions ro;
  ro.tolerance = 5e-3;
  const RelaxedSet<3> set = relaxed_set<3>(w.wall, w.relax_box, n, GhostMap::DensityPreserving, w.eval_box, w.may_move,
                                           3, 1, ro);
  EXPECT_LE(set.bulk.rel_std, 5e-3) << w.name;
  EXPECT_LE(set.wall.rel_std, 5e-3) << w.name;
  const Real H = 2 * set.bulk.h;
  const std::vector<Real>& inner = set.x;
  const RelaxReport& rr = set.bulk;

  Deviations d;
  for (GhostMap map : {GhostMap::DensityPreserving, GhostMap::Mirror}) {
    // every inner particle gets a ghost (as in the paper), so that ghosts out to 2H exist
    const NodeDensityProfile<3> p = node_density_profile<3>(w.wall, inner, rr.h, map, kInfinity, w.eval_box);
    Real sum = 0;
    std::size_t count = 0;
    for (std::size_t g = 0; g < p.s_ghost.size(); ++g)
      if (p.s_ghost[g] > 0 && p.s_ghost[g] <= H && w.evaluated(Eigen::Map<const Vec<3>>(p.x_ghost.data() + 3 * g))) {
        sum += p.n_ghost[g];
        ++count;
      }
    const Real dev = sum / static_cast<Real>(count) / rr.mean - 1;
    (map == GhostMap::Mirror ? d.mirror : d.psi) = dev;
    d.ghosts = count;
  }
  std::printf("[ static ] %-12s %zu inner (bulk std %.2f%% %d it, wall std %.2f%% %d it), H = %.4f, %zu ghosts "
              "in (0, H]: Psi %+.3f%%  Psi0 %+.3f%%\n",
              w.name, inner.size() / 3, 100 * rr.rel_std, rr.iterations, 100 * set.wall.rel_std, set.wall.iterations, H,
              d.ghosts, 100 * d.psi, 100 * d.mirror);
  return d;
}

}  // namespace

TEST(StaticNodeDensity, PeriodicCylinder) {
  // full cross-section, axis periodic over 0.6 (the paper: z in [-3, 3], the same resolution)
  PeriodicBox<3> eval;
  eval.lo = Vec<3>(-2, -2, -0.3);
  eval.hi = Vec<3>(2, 2, 0.3);
  eval.periodic = {false, false, true};
  const Window w{"cylinder", Cylinder<3>{Vec<3>::Zero(), 1, FluidSide::Inside},
                 box(Vec<3>(-1, -1, -0.3), Vec<3>(1, 1, 0.3)), eval, [](const Vec<3>&) { return true; },
                 [](const Vec<3>&) { return true; },                 6 * kPi};
  const Deviations d = run(w);
  EXPECT_LT(std::abs(d.psi), 0.01);
  RecordProperty("psi_deviation_percent", std::to_string(100 * d.psi));
  // the mirror map Psi0 under-fills the layer of a concave wall (measured -16.2%): it must stay
  // clearly wrong, the seed's point (seed 004 §7)
  EXPECT_LT(d.mirror, -0.13);
  RecordProperty("mirror_deviation_percent", std::to_string(100 * d.mirror));
}

TEST(StaticNodeDensity, SpherePolarCap) {
  // cap around +z: ghosts within 18 deg of the pole have all their neighbours' sources in the box
  const Real cos18 = std::cos(18 * kPi / 180);
  const Window w{"sphere", Sphere{Vec<3>::Zero(), 1, FluidSide::Inside},
                 box(Vec<3>(-0.45, -0.45, 0.45), Vec<3>(0.45, 0.45, 1.0)), std::nullopt,
                 [cos18](const Vec<3>& g) { return g[2] > cos18 * g.norm(); },
                 [](const Vec<3>& p) { return std::max(std::abs(p[0]), std::abs(p[1])) < 0.45 - 0.12; },
                 4 * kPi / 3};
  const Deviations d = run(w);
  EXPECT_LT(std::abs(d.psi), 0.01);
  RecordProperty("psi_deviation_percent", std::to_string(100 * d.psi));
  // the mirror map Psi0 under-fills the layer of a concave wall (measured -18.6%): it must stay
  // clearly wrong, the seed's point (seed 004 §7)
  EXPECT_LT(d.mirror, -0.15);
  RecordProperty("mirror_deviation_percent", std::to_string(100 * d.mirror));
}

TEST(StaticNodeDensity, TorusSector) {
  // R/a = 3, the full poloidal cross-section around toroidal angle 0, ghosts with |phi| < 0.05
  const Window w{"torus R/a=3", Torus{Vec<3>::Zero(), 3, 1, FluidSide::Inside},
                 box(Vec<3>(1.5, -1.05, -1.05), Vec<3>(4.1, 1.05, 1.05)), std::nullopt,
                 [](const Vec<3>& g) { return std::abs(std::atan2(g[1], g[0])) < 0.05; },
                 [](const Vec<3>& p) { return std::abs(p[1]) < 1.05 - 0.28; },                 2 * kPi * kPi * 3};
  const Deviations d = run(w);
  EXPECT_LT(std::abs(d.psi), 0.01);
  RecordProperty("psi_deviation_percent", std::to_string(100 * d.psi));
  // the mirror map Psi0 under-fills the layer of a concave wall (measured -21.6%): it must stay
  // clearly wrong, the seed's point (seed 004 §7)
  EXPECT_LT(d.mirror, -0.17);
  RecordProperty("mirror_deviation_percent", std::to_string(100 * d.mirror));
}

// The 2D scene to come (flow through a periodic lattice of cylinders, seed 004 §8): a circular
// obstacle R = 0.2 in the periodic unit cell. The obstacle's map only exists for
// -s <= (sqrt2 - 1) R = 0.083, and ghosts in (0, H] need ghosts out to 2H, so H = 0.04 here
// (about 3 600 fluid particles).
TEST(StaticNodeDensity, PeriodicCircleObstacle2D) {
  PeriodicBox<2> cell;
  cell.lo = Vec<2>(-0.5, -0.5);
  cell.hi = Vec<2>(0.5, 0.5);
  cell.periodic = {true, true};
  const Real h = 0.02, dx = h / 1.3;
  const std::size_t n_box = static_cast<std::size_t>(std::lround(1 / (dx * dx)));
  const Wall<2> wall = Cylinder<2>{Vec<2>::Zero(), 0.2, FluidSide::Outside};
  RelaxOptions ro;
  ro.tolerance = 7e-3;  // the 2D near-wall stage creeps below 0.7% (1200 iterations to 0.5%)
  const RelaxedSet<2> set = relaxed_set<2>(wall, cell, n_box, GhostMap::DensityPreserving, cell,
                                           [](const Vec<2>&) { return true; }, 3, 1, ro);
  ASSERT_LE(set.wall.rel_std, 7e-3);
  const Real H = 2 * set.bulk.h;
  Real dev[2] = {0, 0};
  std::size_t count = 0;
  for (GhostMap map : {GhostMap::DensityPreserving, GhostMap::Mirror}) {
    // layer: every particle the obstacle map can take (beyond it the report counts them)
    const NodeDensityProfile<2> p = node_density_profile<2>(wall, set.x, set.bulk.h, map, 0.08, cell);
    EXPECT_EQ(p.invalid, 0u);
    const BinMean g = mean_in_range(p.s_ghost, p.n_ghost, 0, H);
    const BinMean interior = mean_in_range(p.s_inner, p.n_inner, -kInfinity, -H);
    dev[map == GhostMap::Mirror] = g.mean / interior.mean - 1;
    count = g.count;
  }
  std::printf("[ static ] circle 2D    %zu fluid, H = %.3f, %zu ghosts in (0, H]: Psi %+.3f%%  Psi0 %+.3f%%\n",
              set.x.size() / 2, H, count, 100 * dev[0], 100 * dev[1]);
  EXPECT_LT(std::abs(dev[0]), 0.01);
  EXPECT_GT(dev[1], 0.20);  // the mirror over-fills the layer outside a convex obstacle (measured +25.2%)
  RecordProperty("psi_deviation_percent", std::to_string(100 * dev[0]));
  RecordProperty("mirror_deviation_percent", std::to_string(100 * dev[1]));
}
