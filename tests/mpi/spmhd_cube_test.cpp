// The distributed SpmhdScheme in 3D: a perturbed cubic lattice of 1,000 particles in the periodic
// unit cube with Orszag-Tang-like fields plus a z-dependence (rho = 1, u = 1.5), constrained
// cleaning with artificial resistivity: 60 fixed BS23 steps in 6 advances on 1-4 ranks, migrated
// after each (migrate_spmhd; repartitioned after the 3rd), resized after each (the serial run at
// the same points). Every state entry and h, rho, div B of every particle, matched by global id,
// equal the serial run's bit for bit (the 3D halo: periodic images along three axes).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mpi_env.hpp"
#include "serial_comparison.hpp"
#include "sphark/parallel/global_state.hpp"
#include "sphark/schemes/spmhd/spmhd_migration.hpp"

namespace sphark {
namespace {

using testing::world;

constexpr int kSide = 10;
constexpr Real kDt = 5e-3;
constexpr int kChunks = 6, kStepsPerChunk = 10, kRepartitionChunk = 3;

PeriodicBox<3> unit_cube() {
  PeriodicBox<3> box;
  box.periodic = {true, true, true};
  return box;
}

SpmhdOptions cube_options() {
  SpmhdOptions o;
  o.gamma = 5.0 / 3.0;
  o.cleaning = Cleaning::Constrained;
  o.sigma = 0.3;
  o.alpha_b = 0.5;
  o.h_initial = o.eta / kSide;
  return o;
}

struct Cube {
  SpmhdScheme<3> scheme;
  std::vector<Real> y0;
};

Cube make_cube() {
  const std::size_t n = kSide * kSide * kSide;
  const Real dx = 1.0 / kSide, tp = 2 * kPi, b0 = 1 / std::sqrt(4 * kPi);
  Cube c{SpmhdScheme<3>(std::vector<Real>(n, dx * dx * dx), cube_options(), unit_cube()), {}};
  c.y0.assign(c.scheme.size(), 0);
  const StateLayout& L = c.scheme.layout();
  auto x = vector_field<3>(c.y0.data(), L, Field::Position);
  auto v = vector_field<3>(c.y0.data(), L, Field::Velocity);
  auto B = vector_field<3>(c.y0.data(), L, Field::MagneticField);
  auto u = scalar_field(c.y0.data(), L, Field::InternalEnergy);
  for (std::size_t a = 0; a < n; ++a) {
    const Real px = (a % kSide + 0.5 + 0.05 * std::sin(3.1 * a)) * dx, py = (a / kSide % kSide + 0.5) * dx,
               pz = (a / kSide / kSide + 0.5 + 0.05 * std::cos(1.7 * a)) * dx;
    x.col(a) = Vec<3>(px, py, pz);
    v.col(a) = Vec<3>(-std::sin(tp * py), std::sin(tp * px), 0.3 * std::sin(tp * pz));
    B.col(a) = b0 * Vec<3>(-std::sin(tp * py), std::sin(2 * tp * px), 0.3 * std::cos(tp * pz));
    u(a) = 1.5;
  }
  return c;
}

testing::RunOutcome run(bool distributed) {
  Cube c = make_cube();
  const StateLayout whole = c.scheme.layout();
  std::vector<std::int64_t> ids(c.scheme.particles());
  for (std::size_t a = 0; a < ids.size(); ++a) ids[a] = static_cast<std::int64_t>(a);
  std::vector<Real> y = c.y0;
  std::optional<DistributedParticles<3>> parts;
  if (distributed) {
    parts.emplace(world(), c.y0.data() + whole.offset(Field::Position), c.scheme.particles(), unit_cube());
    y = share_of(whole, c.y0, parts->ids());
    c.scheme.distribute(world(), parts->ids());
  }
  auto stepper = make_stepper(c.scheme, testing::comparison_options("ARKODE_BOGACKI_SHAMPINE_4_2_3", kDt, 1e-6,
                                                                    distributed ? world() : Communicator{}),
                              0.0, y.data());
  testing::RunOutcome out;
  Real t = 0;
  for (int k = 1; k <= kChunks; ++k) {
    EXPECT_EQ(stepper->advance(k * kStepsPerChunk * kDt, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
    if (k == kChunks) break;
    if (parts) {
      const std::size_t sent = migrate_spmhd(*parts, c.scheme, y, nullptr, k == kRepartitionChunk);
      out.migrated += sent;
      if (k != kRepartitionChunk) out.moved += sent;
    }
    stepper->resize({y.data(), nullptr, nullptr});
  }
  out.steps = stepper->stats().steps;
  EXPECT_EQ(c.scheme.evaluate(t, y.data()), 0) << c.scheme.last_error();
  const StateLayout& L = c.scheme.layout();
  const std::vector<std::int64_t>& mine = parts ? parts->ids() : ids;
  for (std::size_t a = 0; a < mine.size(); ++a) {
    std::vector<Real>& row = out.fields[mine[a]];
    for (const Field f : L.fields())
      for (int k = 0; k < L.components(f); ++k) row.push_back(y[L.offset(f) + L.components(f) * a + k]);
    row.insert(row.end(), {c.scheme.h()[a], c.scheme.rho()[a], c.scheme.div_b()[a]});
  }
  return out;
}

TEST(SpmhdCube, CleaningWithResistivityMatchesSerialBitForBit) {
  const testing::RunOutcome serial = run(false), dist = run(true);
  testing::expect_equal_to_serial("3D cube, cleaning+resistivity", serial, dist, kChunks * kStepsPerChunk);
}

}  // namespace
}  // namespace sphark
