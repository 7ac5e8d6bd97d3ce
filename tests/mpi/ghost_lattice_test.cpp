// The distributed GhostWcsph on the lattice of cylinders (seed 004 §8: the periodic cell with a
// cylinder of radius 0.2, ghost particles across its wall; 1,000 particles from the relaxed
// random start): 120 fixed steps on 1-4 ranks (DistributedParticles: RCB domains of the initial
// positions, wrapping), the particles migrated to their RCB owners every 10 steps with their
// state and what their density solve reached (migrate_ghost_wcsph; repartitioned at step 60),
// Stepper::resize after each (the serial run resized at the same points to the same state).
// Every field of every particle, matched by global id (x, v of the state; rho and h of the
// scheme), equals the serial run's bit for bit, for BS23 and the default leapfrog with
// dt = max_stable_dt (the step from every rank's maxima; its derivative migrated along).
#include <gtest/gtest.h>

#include <string>

#include "mpi_env.hpp"
#include "serial_comparison.hpp"
#include "sphark/parallel/global_state.hpp"
#include "sphark/scenes/cylinder_lattice/lattice_run.hpp"
#include "sphark/schemes/ghost_wcsph/ghost_migration.hpp"

namespace sphark {
namespace {

using testing::world;
using Fields = testing::FieldsById;
using Outcome = testing::RunOutcome;

constexpr std::size_t kParticles = 1000;
constexpr Real kDt = 2e-3;  // ~0.5 of the CFL step 0.25 h / (c + |v| + 1.2 alpha c) at this resolution
constexpr int kChunks = 12, kStepsPerChunk = 10, kRepartitionChunk = 6;

LatticeRunConfig small_lattice() {
  LatticeRunConfig c;
  c.particles = kParticles;
  c.relax_iterations = 20;
  return c;
}

// Per particle by global id: x, v, rho, h (collective when distributed: the scheme prepares y).
Fields collect(LatticeSystem& s, const std::vector<Real>& y, const std::vector<std::int64_t>& ids) {
  EXPECT_EQ(s.prepare(y.data()), 0) << s.last_error();
  Fields out;
  const Real* x = y.data() + s.position_offset();
  const Real* v = y.data() + s.velocity_offset();
  for (std::size_t a = 0; a < ids.size(); ++a)
    out[ids[a]] = {x[2 * a], x[2 * a + 1], v[2 * a], v[2 * a + 1], s.density()[a], s.smoothing_length()[a]};
  return out;
}

StepperOptions options(const std::string& method, const Communicator& comm) {
  StepperOptions o = testing::comparison_options(method, kDt, 1e-6, comm);
  if (method == "leapfrog") o.fixed_dt = 0;  // dt = max_stable_dt, reduced over the ranks
  return o;
}

template <class Between>
Outcome advance_chunks(LatticeSystem& s, std::vector<Real>& y, const std::vector<std::int64_t>& ids, Stepper& stepper,
                       Real chunk, Between&& between) {
  Real t = 0;
  Outcome out;
  for (int k = 1; k <= kChunks; ++k) {
    EXPECT_EQ(stepper.advance(k * chunk, y.data(), t), AdvanceStatus::Reached) << stepper.failure_reason();
    if (k < kChunks) between(k, out);
  }
  out.steps = stepper.stats().steps;
  out.fields = collect(s, y, ids);
  return out;
}

std::vector<Real> initial_state(const LatticeSystem& s, const std::vector<Real>& x0) {
  std::vector<Real> y(s.size(), 0.0);  // at rest
  std::copy(x0.begin(), x0.end(), y.begin() + static_cast<std::ptrdiff_t>(s.position_offset()));
  return y;
}

Outcome run_serial(const std::string& method, const std::vector<Real>& x0, const LatticeParams& p) {
  LatticeSystem s(kParticles, p);
  std::vector<Real> y = initial_state(s, x0);
  auto stepper = make_stepper(s, options(method, Communicator{}), 0.0, y.data());
  std::vector<std::int64_t> ids(kParticles);
  for (std::size_t a = 0; a < ids.size(); ++a) ids[a] = static_cast<std::int64_t>(a);
  return advance_chunks(s, y, ids, *stepper, kStepsPerChunk * kDt, [&](int, Outcome&) {
    std::vector<Real> carried = stepper->carried_data();
    stepper->resize({y.data(), nullptr, carried.empty() ? nullptr : carried.data()});
  });
}

// empty_start: every particle on the last rank for the first chunk, then the RCB owners.
Outcome run_distributed(const std::string& method, const std::vector<Real>& x0, const LatticeParams& p,
                        bool empty_start) {
  LatticeSystem s(kParticles, p);
  const StateLayout whole = s.layout();
  DistributedParticles<2> parts(world(), x0.data(), kParticles, lattice_box(p));
  if (empty_start) {
    std::vector<std::int64_t> all;
    if (world().rank() == world().size() - 1)
      for (std::size_t a = 0; a < kParticles; ++a) all.push_back(static_cast<std::int64_t>(a));
    parts.assign(all);
  }
  std::vector<Real> y = share_of(whole, initial_state(s, x0), parts.ids());
  s.distribute(world(), parts.ids());
  auto stepper = make_stepper(s, options(method, world()), 0.0, y.data());
  return advance_chunks(s, y, parts.ids(), *stepper, kStepsPerChunk * kDt, [&](int k, Outcome& out) {
    std::vector<Real> carried = stepper->carried_data();
    const bool with = world().allreduce(std::int64_t(carried.empty() ? 0 : 1), ReduceOp::Max) == 1;
    const std::size_t sent = migrate_ghost_wcsph(parts, s, y, with ? &carried : nullptr, k == kRepartitionChunk);
    out.migrated += sent;
    if (k != kRepartitionChunk) out.moved += sent;
    stepper->resize({y.data(), nullptr, with ? carried.data() : nullptr});
  });
}

void check_lattice(const std::string& name, const std::string& method, bool empty_start = false) {
  const LatticeRunConfig cfg = small_lattice();
  const LatticeParams p = lattice_params(cfg.params, cfg.particles);
  const std::vector<Real> x0 = initial_positions(cfg);
  const Outcome serial = run_serial(method, x0, p), dist = run_distributed(method, x0, p, empty_start);
  testing::expect_equal_to_serial(name, serial, dist, method == "leapfrog" ? 0 : kChunks * kStepsPerChunk);
}

TEST(GhostLattice, Bs23MatchesSerialBitForBit) { check_lattice("lattice, BS23", "ARKODE_BOGACKI_SHAMPINE_4_2_3"); }

TEST(GhostLattice, LeapfrogOnTheStableStepMatchesSerialBitForBit) { check_lattice("lattice, leapfrog", "leapfrog"); }

// Ranks without particles take part in every collective step.
TEST(GhostLattice, RanksWithoutParticlesMatchSerialBitForBit) {
  check_lattice("lattice, all on one rank first", "ARKODE_BOGACKI_SHAMPINE_4_2_3", true);
}

}  // namespace
}  // namespace sphark
