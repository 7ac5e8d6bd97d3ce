// Ghost generation: placement on the normal line at s' = psi(s), copied fields, velocity
// boundary conditions, periodic walls, error reporting, no allocation after the first call.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "sphark/boundaries/ghosts.hpp"

using namespace sphark;

namespace {
std::vector<Real> random_in_ball(std::size_t n, int dim, Real radius, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Real> U(-radius, radius);
  std::vector<Real> x;
  while (x.size() < n * dim) {
    Real p[3] = {U(rng), U(rng), U(rng)}, r2 = 0;
    for (int k = 0; k < dim; ++k) r2 += p[k] * p[k];
    if (r2 < radius * radius)
      for (int k = 0; k < dim; ++k) x.push_back(p[k]);
  }
  return x;
}
}  // namespace

TEST(Ghosts, PlacedOnNormalLineAtPsiWithFieldsAndFreeSlip) {
  const std::size_t n = 4000;
  const std::vector<Real> x = random_in_ball(n, 3, 2.9, 7);  // inside torus tube or not
  std::vector<Real> v(3 * n), mass(n), rho(n);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<Real> U(-1, 1);
  for (auto& e : v) e = U(rng);
  for (std::size_t i = 0; i < n; ++i) mass[i] = 1 + 0.1 * U(rng), rho[i] = 1000 + U(rng);

  const Torus torus{Vec<3>::Zero(), 2.2, 0.7, FluidSide::Inside};
  GhostOptions opt;
  opt.width = 0.3;
  GhostLayer<3> layer;
  const GhostReport rep = layer.append(Wall<3>(torus), x.data(), v.data(), n, opt);
  ASSERT_EQ(rep.invalid, 0u);
  std::size_t expected = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Real s = torus.coordinates(Eigen::Map<const Vec<3>>(x.data() + 3 * i)).s;
    expected += (s > -opt.width && s <= 0);
  }
  EXPECT_EQ(layer.size(), expected);
  EXPECT_GT(layer.size(), 100u);

  std::vector<Real> gm(layer.size()), grho(layer.size());
  layer.gather_scalar(mass.data(), gm.data());
  layer.gather_scalar(rho.data(), grho.data());
  for (std::size_t g = 0; g < layer.size(); ++g) {
    const std::size_t i = layer.sources()[g];
    const Vec<3> xi = Eigen::Map<const Vec<3>>(x.data() + 3 * i);
    const Vec<3> xg = Eigen::Map<const Vec<3>>(layer.positions() + 3 * g);
    const WallCoords ci = torus.coordinates(xi), cg = torus.coordinates(xg);
    EXPECT_NEAR(cg.s, torus.map(ci.s, ci.u, ci.v).psi, 1e-13);  // s' = psi(s)
    EXPECT_NEAR(cg.u, ci.u, 1e-12);                              // same normal line
    EXPECT_NEAR(cg.v, ci.v, 1e-12);
    EXPECT_EQ(gm[g], mass[i]);
    EXPECT_EQ(grho[g], rho[i]);
    // free slip: normal component reversed, tangential kept
    const Vec<3> nrm = torus.locate(xi).normal;
    const Vec<3> vi = Eigen::Map<const Vec<3>>(v.data() + 3 * i);
    const Vec<3> vg = Eigen::Map<const Vec<3>>(layer.velocities() + 3 * g);
    EXPECT_NEAR(vg.dot(nrm), -vi.dot(nrm), 1e-14);
    EXPECT_NEAR((vg - vg.dot(nrm) * nrm - (vi - vi.dot(nrm) * nrm)).norm(), 0, 1e-14);
  }
}

TEST(Ghosts, NoSlipAndMirrorOption) {
  const std::vector<Real> x = random_in_ball(2000, 3, 1, 11);
  std::vector<Real> v(x.size(), 0.5);
  const Sphere sphere{Vec<3>::Zero(), 1, FluidSide::Inside};
  GhostOptions opt;
  opt.width = 0.2;
  opt.map = GhostMap::Mirror;
  opt.velocity = VelocityBc::NoSlip;
  GhostLayer<3> layer;
  layer.append(Wall<3>(sphere), x.data(), v.data(), 2000, opt);
  ASSERT_GT(layer.size(), 0u);
  for (std::size_t g = 0; g < layer.size(); ++g) {
    const std::size_t i = layer.sources()[g];
    const Real si = sphere.coordinates(Eigen::Map<const Vec<3>>(x.data() + 3 * i)).s;
    EXPECT_NEAR(layer.wall_s()[g], -si, 1e-15);
    EXPECT_NEAR(sphere.coordinates(Eigen::Map<const Vec<3>>(layer.positions() + 3 * g)).s, -si, 1e-14);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(layer.velocities()[3 * g + k], -0.5);
  }
}

// 2D circular obstacle in a periodic cell (the lattice-of-cylinders scene): a particle near the
// opposite face sees the obstacle through the minimum image; its ghost is wrapped into the box.
TEST(Ghosts, PeriodicCircleObstacle) {
  PeriodicBox<2> box;
  box.lo = Vec<2>(-0.5, -0.5);
  box.hi = Vec<2>(0.5, 0.5);
  box.periodic = {true, true};
  const Cylinder<2> obstacle{Vec<2>(0.45, 0), 0.2, FluidSide::Outside};
  const std::vector<Real> x = {-0.3, 0.0,   // image at 0.7: 0.25 from the centre, s = -0.05
                               0.0, 0.0,    // 0.45 from the centre: s = -0.25
                               0.45, 0.28};  // s = -0.08
  GhostOptions opt;
  opt.width = 0.2;
  GhostLayer<2> layer;
  const GhostReport rep = layer.append(Wall<2>(obstacle), x.data(), nullptr, 3, opt, &box);
  ASSERT_EQ(rep.generated, 2u);
  EXPECT_EQ(layer.sources()[0], 0u);
  EXPECT_EQ(layer.sources()[1], 2u);
  // particle 0 at image (0.7, 0): ghost at radius R - psi on the same line, wrapped into the box
  const Real psi0 = cylinder_map(-0.05, 0.2, FluidSide::Outside).psi;
  EXPECT_NEAR(layer.positions()[0], 0.45 + 0.2 - psi0 - 1.0, 1e-14);
  EXPECT_NEAR(layer.positions()[1], 0.0, 1e-14);
  const Real psi2 = cylinder_map(-0.08, 0.2, FluidSide::Outside).psi;
  EXPECT_NEAR(layer.positions()[3], 0.2 - psi2, 1e-14);
}

// Regenerating ghosts every RHS evaluation: after the first call the buffers are reused.
TEST(Ghosts, NoAllocationAfterFirstCall) {
  std::vector<Real> x = random_in_ball(3000, 2, 0.5, 5);
  for (std::size_t i = 0; i < x.size(); i += 2) x[i] += 0.0;
  const Cylinder<2> obstacle{Vec<2>::Zero(), 0.2, FluidSide::Outside};
  std::vector<Real> fluid;
  for (std::size_t i = 0; i < x.size(); i += 2)
    if (std::hypot(x[i], x[i + 1]) > 0.2) fluid.insert(fluid.end(), {x[i], x[i + 1]});
  const std::size_t n = fluid.size() / 2;
  GhostOptions opt;
  opt.width = 0.06;
  GhostLayer<2> layer;
  layer.append(Wall<2>(obstacle), fluid.data(), nullptr, n, opt);
  const Real* p = layer.positions();
  const std::size_t cap = layer.capacity(), first = layer.size();
  for (int step = 0; step < 20; ++step) {
    for (auto& e : fluid) e *= 1.0 + 1e-3 * ((step % 2) ? 1 : -1);  // particles move
    layer.clear();
    layer.append(Wall<2>(obstacle), fluid.data(), nullptr, n, opt);
    EXPECT_EQ(layer.positions(), p);
    EXPECT_EQ(layer.capacity(), cap);
  }
  EXPECT_GT(first, 0u);
}

TEST(Ghosts, InvalidMapIsReportedOrThrown) {
  // an obstacle whose ghost layer is wider than (sqrt2 - 1) R: the deepest particles cannot be mapped
  const Cylinder<2> obstacle{Vec<2>::Zero(), 0.2, FluidSide::Outside};
  const std::vector<Real> x = {0.25, 0.0, 0.3, 0.0};  // s = -0.05 (ok), s = -0.1 (> 0.0828)
  GhostOptions opt;
  opt.width = 0.15;
  GhostLayer<2> layer;
  try {
    layer.append(Wall<2>(obstacle), x.data(), nullptr, 2, opt);
    FAIL() << "expected std::domain_error";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("particle 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no real solution"), std::string::npos) << e.what();
  }
  layer.clear();
  opt.on_invalid = OnInvalid::Skip;
  const GhostReport rep = layer.append(Wall<2>(obstacle), x.data(), nullptr, 2, opt);
  EXPECT_EQ(rep.generated, 1u);
  EXPECT_EQ(rep.invalid, 1u);
  EXPECT_EQ(rep.first_invalid, 1u);
  EXPECT_EQ(rep.first_status, MapStatus::NoRealSolution);
  for (std::size_t k = 0; k < 2 * layer.size(); ++k) EXPECT_TRUE(std::isfinite(layer.positions()[k]));
}
