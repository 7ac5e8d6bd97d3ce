// The distributed SpmhdScheme with fixed particles: the cleaning subsystem of the free-boundary
// disc (seed 000 §IV-A, spacing 0.06: 872 particles; the state is B and psi, the positions fixed
// and open). 100 fixed BS23 steps on 1-4 ranks (RCB domains of the positions, which never
// change: no migration); B, psi and div B of every particle, matched by global id, equal the
// serial run's bit for bit, for the constrained form with damping and the non-conservative one
// without.
#include <gtest/gtest.h>

#include <string>

#include "mpi_env.hpp"
#include "serial_comparison.hpp"
#include "sphark/parallel/distributed_particles.hpp"
#include "sphark/parallel/global_state.hpp"
#include "sphark/scenes/cleaning_disc/cleaning_disc.hpp"

namespace sphark {
namespace {

using testing::world;

constexpr Real kSpacing = 0.06, kDt = 2e-3;  // ~0.5 of the cleaning wave's Courant step
constexpr long kSteps = 100;

testing::RunOutcome run(Cleaning form, Real sigma, bool distributed) {
  CleaningDisc disc(form, sigma, kSpacing);
  std::vector<std::int64_t> ids(disc.scheme.particles());
  for (std::size_t a = 0; a < ids.size(); ++a) ids[a] = static_cast<std::int64_t>(a);
  std::vector<Real> y = disc.y0;
  std::optional<DistributedParticles<2>> parts;
  if (distributed) {
    parts.emplace(world(), disc.particles.x.data(), disc.scheme.particles());
    ids = parts->ids();
    y = share_of(disc.scheme.layout(), disc.y0, ids);
    disc.scheme.distribute(world(), ids);
  }
  auto stepper = make_stepper(disc.scheme, testing::comparison_options("ARKODE_BOGACKI_SHAMPINE_4_2_3", kDt, 1e-6,
                                                                       distributed ? world() : Communicator{}),
                              0.0, y.data());
  Real t = 0;
  EXPECT_EQ(stepper->advance(kSteps * kDt, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
  testing::RunOutcome out;
  out.steps = stepper->stats().steps;
  EXPECT_EQ(disc.scheme.evaluate(t, y.data()), 0) << disc.scheme.last_error();
  const StateLayout& L = disc.scheme.layout();
  const Real *B = y.data() + L.offset(Field::MagneticField), *psi = y.data() + L.offset(Field::Psi);
  for (std::size_t a = 0; a < ids.size(); ++a)
    out.fields[ids[a]] = {B[3 * a], B[3 * a + 1], B[3 * a + 2], psi[a], disc.scheme.div_b()[a]};
  return out;
}

void check_disc(const std::string& name, Cleaning form, Real sigma) {
  const testing::RunOutcome serial = run(form, sigma, false), dist = run(form, sigma, true);
  testing::expect_equal_to_serial(name, serial, dist, kSteps, false);
}

TEST(SpmhdCleaningDisc, ConstrainedDampedMatchesSerialBitForBit) {
  check_disc("disc, constrained, sigma 0.2", Cleaning::Constrained, 0.2);
}

TEST(SpmhdCleaningDisc, NonConservativeUndampedMatchesSerialBitForBit) {
  check_disc("disc, non-conservative, sigma 0", Cleaning::NonConservative, 0);
}

}  // namespace
}  // namespace sphark
