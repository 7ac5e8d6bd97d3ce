// The distributed SpmhdScheme on the Orszag-Tang vortex (seed 000 §IV-B, periodic, 24 x 28 = 672
// particles): 120 fixed steps on 1-4 ranks (DistributedParticles: RCB domains of the initial
// positions, wrapping), the particles migrated to their RCB owners every 10 steps with their
// state and h-solve starts (migrate_spmhd; repartitioned at step 60; count, ids, mass and
// momentum checked), Stepper::resize after each. Every field of every particle, matched by
// global id (x, v, u, B, psi of the state; h, rho and div B of the scheme), equals the serial
// run's bit for bit (rows summed in global-id order; every decision of the density solve taken
// by all ranks together), for
// - constrained cleaning with artificial resistivity (the global c_h reduced over the ranks),
//   BS23, and the leapfrog (its carried derivative migrated along),
// - cleaning with a per-particle c_h (local_ch: the halo's records carry their own c_h),
// - no divergence control (no psi in the state).
// An adaptive run (DP5, rtol 1e-5, reproducible norms, steps capped by max_stable_dt) equals a
// serial run with reproducible norms bit for bit, steps included.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "mpi_env.hpp"
#include "serial_comparison.hpp"
#include "sphark/integrate/stepper.hpp"
#include "sphark/parallel/global_state.hpp"
#include "sphark/scenes/orszag_tang/orszag_tang.hpp"
#include "sphark/schemes/spmhd/spmhd_migration.hpp"

namespace sphark {
namespace {

using testing::world;
using Fields = testing::FieldsById;
using Outcome = testing::RunOutcome;

constexpr Real kDt = 1e-3;  // ~0.5 of the cleaning wave's Courant limit at this resolution
constexpr const char* kErk = "ARKODE_BOGACKI_SHAMPINE_4_2_3";
constexpr int kChunks = 12, kStepsPerChunk = 10, kRepartitionChunk = 6;

OrszagTangParams small_vortex() {
  OrszagTangParams p;
  p.nx = 24;
  return p;
}

// Per particle by global id: every state entry, then h, rho, div B (collective when distributed).
Fields collect(SpmhdScheme<2>& s, Real t, const std::vector<Real>& y, const std::vector<std::int64_t>& ids) {
  EXPECT_EQ(s.evaluate(t, y.data()), 0) << s.last_error();
  const StateLayout& L = s.layout();
  const std::vector<Real>&h = s.h(), &rho = s.rho(), &div_b = s.div_b();
  Fields out;
  for (std::size_t a = 0; a < ids.size(); ++a) {
    std::vector<Real>& row = out[ids[a]];
    for (const Field f : L.fields())
      for (int k = 0; k < L.components(f); ++k) row.push_back(y[L.offset(f) + L.components(f) * a + k]);
    row.insert(row.end(), {h[a], rho[a], div_b[a]});
  }
  return out;
}

StepperOptions options(const std::string& method, bool adaptive, const Communicator& comm) {
  return testing::comparison_options(method, adaptive ? 0 : kDt, 1e-5, comm);
}

template <class Between>
Outcome advance_chunks(SpmhdScheme<2>& s, std::vector<Real>& y, const std::vector<std::int64_t>& ids,
                       Stepper& stepper, Between&& between) {
  Real t = 0;
  Outcome out;
  for (int k = 1; k <= kChunks; ++k) {
    EXPECT_EQ(stepper.advance(k * kStepsPerChunk * kDt, y.data(), t), AdvanceStatus::Reached)
        << stepper.failure_reason();
    if (k < kChunks) between(k, out);
  }
  out.steps = stepper.stats().steps;
  out.fields = collect(s, t, y, ids);
  return out;
}

Outcome run_serial(const std::string& variant, const OrszagTangParams& p, const std::string& method, bool adaptive) {
  OrszagTang ot(variant, p);
  std::vector<Real> y = ot.y0;
  auto stepper = make_stepper(ot.scheme, options(method, adaptive, Communicator{}), 0.0, y.data());
  std::vector<std::int64_t> ids(ot.scheme.particles());  // serially particle a has global id a
  for (std::size_t a = 0; a < ids.size(); ++a) ids[a] = static_cast<std::int64_t>(a);
  // resized at the same points as the distributed run (to the same state): ARKODE's resize
  // restarts the step controller's history (without it the adaptive run differs by 6e-14)
  return advance_chunks(ot.scheme, y, ids, *stepper, [&](int, Outcome&) {
    std::vector<Real> carried = stepper->carried_data();
    stepper->resize({y.data(), nullptr, carried.empty() ? nullptr : carried.data()});
  });
}

// empty_start: every particle on the last rank for the first chunk (the others without any),
// then the RCB owners.
Outcome run_distributed(const std::string& variant, const OrszagTangParams& p, const std::string& method,
                        bool adaptive, bool empty_start = false) {
  OrszagTang ot(variant, p);
  const StateLayout whole = ot.scheme.layout();
  DistributedParticles<2> parts(world(), ot.y0.data() + whole.offset(Field::Position), ot.scheme.particles(),
                                unit_periodic_box());
  std::vector<std::int64_t> start = parts.ids();
  if (empty_start) {
    start.clear();
    if (world().rank() == world().size() - 1)
      for (std::size_t a = 0; a < ot.scheme.particles(); ++a) start.push_back(static_cast<std::int64_t>(a));
    parts.assign(start);
  }
  std::vector<Real> y = share_of(whole, ot.y0, parts.ids());
  ot.scheme.distribute(world(), parts.ids());
  auto stepper = make_stepper(ot.scheme, options(method, adaptive, world()), 0.0, y.data());
  return advance_chunks(ot.scheme, y, parts.ids(), *stepper, [&](int k, Outcome& out) {
    std::vector<Real> carried = stepper->carried_data();
    const bool with = world().allreduce(std::int64_t(carried.empty() ? 0 : 1), ReduceOp::Max) == 1;
    const std::size_t sent = migrate_spmhd(parts, ot.scheme, y, with ? &carried : nullptr, k == kRepartitionChunk);
    out.migrated += sent;
    if (k != kRepartitionChunk) out.moved += sent;
    stepper->resize({y.data(), nullptr, with ? carried.data() : nullptr});
  });
}

void check_vortex(const std::string& name, const std::string& variant, const OrszagTangParams& p,
                  const std::string& method = kErk, bool adaptive = false, bool empty_start = false) {
  const Outcome serial = run_serial(variant, p, method, adaptive),
                dist = run_distributed(variant, p, method, adaptive, empty_start);
  testing::expect_equal_to_serial(name, serial, dist, adaptive ? 0 : kChunks * kStepsPerChunk);
}

TEST(SpmhdOrszagTang, CleaningWithResistivityMatchesSerialBitForBit) {
  check_vortex("cleaning+resistivity", "cleaning+resistivity", small_vortex());
}

TEST(SpmhdOrszagTang, LocalCleaningSpeedMatchesSerialBitForBit) {
  OrszagTangParams p = small_vortex();
  p.local_ch = true;
  check_vortex("cleaning, local c_h", "cleaning", p);
}

TEST(SpmhdOrszagTang, NoControlLeapfrogMatchesSerialBitForBit) {
  check_vortex("none, leapfrog", "none", small_vortex(), "leapfrog");  // its carried derivative migrates along
}

// Ranks without particles take part in every collective step (and lists of nothing).
TEST(SpmhdOrszagTang, RanksWithoutParticlesMatchSerialBitForBit) {
  check_vortex("cleaning, all on one rank first", "cleaning", small_vortex(), kErk, false, true);
}

TEST(SpmhdOrszagTang, AdaptiveRunMatchesSerialWithReproducibleNorms) {
  check_vortex("cleaning, DP5", "cleaning", small_vortex(), "ARKODE_DORMAND_PRINCE_7_4_5", true);
}

}  // namespace
}  // namespace sphark
