// The distributed WcsphSystem on the water drop (seed 000 §IV-D, 872 particles): 120 fixed
// steps on 1-4 ranks (DistributedDrop: RCB domains of the initial positions), the particles
// migrated to their RCB owners every 10 steps (repartitioned at step 60; migrate() checks count,
// ids, mass and momentum), Stepper::resize after each. Every field of every particle, matched by global
// id (x, v, rho, psi of the state; pressure and div v of the frame), equals the serial run's
// bit for bit (rows sorted by global id: the same terms in the same order), for
// - the delta-SPH scheme with Antuono's correction and cleaning (per RHS: the halo plan check,
//   the state's exchange, the renormalised density gradients' exchange), BS23 and leapfrog
//   (its carried kick migrated along),
// - the seed's plain scheme (delta = 0) with cleaning (no gradient exchange),
// - Molteni & Colagrossi's uncorrected diffusion with viscosity, no cleaning (no psi).
// An adaptive run (DP5, rtol 1e-6, steps capped by max_stable_dt: a collective RHS through the
// memoised evaluation, and the maxima of |v|, c and |a| over every rank) equals a serial run
// with reproducible norms bit for bit, steps included.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "mpi_env.hpp"
#include "serial_comparison.hpp"
#include "sphark/integrate/stepper.hpp"
#include "sphark/scenes/water_drop/distributed_drop.hpp"

namespace sphark {
namespace {

using testing::world;
using Fields = testing::FieldsById;
using Outcome = testing::RunOutcome;

constexpr Real kDt = 2e-5;  // ~0.6 of the CFL limit 0.25 h / (c_s + |v|)
constexpr const char* kErk = "ARKODE_BOGACKI_SHAMPINE_4_2_3";
constexpr int kChunks = 12, kStepsPerChunk = 10, kRepartitionChunk = 6;

WaterDropConfig small_drop() {
  WaterDropConfig c;
  c.spacing = 0.06;  // 872 particles
  return c;
}

// The frame's fields (collective when distributed: div v and pressure evaluate the RHS).
Fields collect(WcsphModel& model, Real t, const std::vector<Real>& y, const std::vector<std::int64_t>& ids) {
  const ParticleFrame f = model.frame(t, y.data());
  Fields out;
  for (std::size_t a = 0; a < f.count; ++a) {
    std::vector<Real>& row = out[ids[a]];
    row = {f.positions[2 * a], f.positions[2 * a + 1]};
    for (const PointArray& arr : f.arrays)
      for (int k = 0; k < arr.components; ++k) row.push_back(arr.data[arr.components * a + k]);
  }
  return out;
}

StepperOptions options(const std::string& method, bool adaptive, const Communicator& comm) {
  return testing::comparison_options(method, adaptive ? 0 : kDt, 1e-6, comm);
}

// From t = 0 in kChunks advances of kStepsPerChunk x kDt, between(chunk) after each but the last.
template <class Between>
Outcome advance_chunks(WcsphModel& model, std::vector<Real>& y, const std::vector<std::int64_t>& ids, Stepper& stepper,
                       Between&& between) {
  Real t = 0;
  Outcome out;
  for (int k = 1; k <= kChunks; ++k) {
    EXPECT_EQ(stepper.advance(k * kStepsPerChunk * kDt, y.data(), t), AdvanceStatus::Reached)
        << stepper.failure_reason();
    if (k < kChunks) out.migrated += between(k);
  }
  out.steps = stepper.stats().steps;
  out.fields = collect(model, t, y, ids);
  return out;
}

Outcome run_serial(const WaterDropConfig& cfg, const std::string& method, bool adaptive) {
  WaterDrop drop = make_water_drop(cfg);
  std::vector<Real> y = drop.y0;
  auto stepper = make_stepper(drop.model->system(), options(method, adaptive, Communicator{}), 0.0, y.data());
  std::vector<std::int64_t> ids(drop.particles());  // serially particle a has global id a
  for (std::size_t a = 0; a < ids.size(); ++a) ids[a] = static_cast<std::int64_t>(a);
  return advance_chunks(*drop.model, y, ids, *stepper, [](int) { return std::size_t(0); });
}

// On the world's ranks, migrating to the RCB owners after every chunk (repartitioned after
// chunk kRepartitionChunk).
Outcome run_distributed(const WaterDropConfig& cfg, const std::string& method, bool adaptive) {
  DistributedDrop d(cfg, world());
  auto stepper = make_stepper(d.model().system(), options(method, adaptive, world()), 0.0, d.state().data());
  std::size_t moved = 0;
  Outcome out = advance_chunks(d.model(), d.state(), d.ids(), *stepper, [&](int k) {
    const std::size_t sent = d.migrate(*stepper, k == kRepartitionChunk);
    if (k != kRepartitionChunk) moved += sent;
    return sent;
  });
  out.moved = moved;
  return out;
}

// The distributed run against the serial one (on every rank): every particle once, every
// field equal. Returns the largest relative difference (0: bit for bit).
void check_drop(const std::string& name, const WaterDropConfig& cfg, const std::string& method = kErk,
                bool adaptive = false) {
  const Outcome serial = run_serial(cfg, method, adaptive), dist = run_distributed(cfg, method, adaptive);
  testing::expect_equal_to_serial(name, serial, dist, adaptive ? 0 : kChunks * kStepsPerChunk);
}

TEST(WcsphDrop, DeltaSphCleanedMatchesSerialBitForBit) { check_drop("delta-SPH cleaned", small_drop()); }

TEST(WcsphDrop, SeedSchemeMatchesSerialBitForBit) {
  WaterDropConfig c = small_drop();
  c.delta = 0;  // the seed's eqs. (26)-(28) with cleaning
  check_drop("seed cleaned", c);
}

TEST(WcsphDrop, UncorrectedDiffusionWithViscosityMatchesSerialBitForBit) {
  WaterDropConfig c = small_drop();
  c.diffusion_correction = false;
  c.cleaning = false;
  c.alpha = 0.1;
  check_drop("Molteni-Colagrossi control, alpha 0.1", c);
}

TEST(WcsphDrop, LeapfrogMatchesSerialBitForBit) {
  check_drop("delta-SPH cleaned, leapfrog", small_drop(), "leapfrog");  // its carried kick migrates along
}

TEST(WcsphDrop, AdaptiveRunMatchesSerialWithReproducibleNorms) {
  check_drop("delta-SPH cleaned, DP5", small_drop(), "ARKODE_DORMAND_PRINCE_7_4_5", true);
}

}  // namespace
}  // namespace sphark
