// StateLayout offsets and the zero-copy path between our state array, its Eigen views and a
// SUNDIALS serial N_Vector wrapping the same memory (what the ARKODE steppers hand to the RHS).
#include <gtest/gtest.h>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include <cmath>

#include "sphark/state/state_layout.hpp"

using namespace sphark;

TEST(StateLayout, FieldMajorOffsetsAndSizes) {
  StateLayout L(5);
  L.add(Field::Position, 2).add(Field::Velocity, 2).add(Field::Density, 1).add(Field::Psi, 1);
  EXPECT_EQ(L.offset(Field::Position), 0u);
  EXPECT_EQ(L.offset(Field::Velocity), 10u);
  EXPECT_EQ(L.offset(Field::Density), 20u);
  EXPECT_EQ(L.offset(Field::Psi), 25u);
  EXPECT_EQ(L.size(), 30u);
  EXPECT_FALSE(L.has(Field::MagneticField));
  EXPECT_THROW(L.offset(Field::MagneticField), std::out_of_range);
  EXPECT_THROW(L.add(Field::Density, 1), std::invalid_argument);
  EXPECT_THROW(vector_field<3>(static_cast<Real*>(nullptr), L, Field::Position), std::logic_error);
}

TEST(StateLayout, PerFieldToleranceFillsEachBlock) {
  StateLayout L(3);
  L.add(Field::Position, 2).add(Field::Density, 1);
  const auto atol = per_field_tolerance(L, {{Field::Density, 0.5}, {Field::Psi, 9.0}}, 1e-3);
  ASSERT_EQ(atol.size(), 9u);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(atol[k], 1e-3);
  for (int k = 6; k < 9; ++k) EXPECT_EQ(atol[k], 0.5);
}

TEST(StateLayout, NVectorRoundTripIsZeroCopy) {
  StateLayout L(4);
  L.add(Field::Position, 3).add(Field::Velocity, 3).add(Field::Density, 1);
  std::vector<Real> y(L.size());
  auto x = vector_field<3>(y.data(), L, Field::Position);
  auto rho = scalar_field(y.data(), L, Field::Density);
  for (Index a = 0; a < 4; ++a) {
    x.col(a) = Vec<3>(a, 10 + a, 20 + a);
    rho[a] = 1000 + a;
  }
  SUNContext ctx = nullptr;
  ASSERT_EQ(SUNContext_Create(nullptr, &ctx), 0);
  N_Vector v = N_VMake_Serial(static_cast<sunindextype>(y.size()), y.data(), ctx);
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(N_VGetArrayPointer(v), y.data());  // same memory, no copy
  EXPECT_EQ(N_VGetLength(v), static_cast<sunindextype>(L.size()));
  N_VScale(2.0, v, v);  // a vector operation ARKODE would do, seen through the Eigen views
  for (Index a = 0; a < 4; ++a) {
    EXPECT_EQ(x(1, a), 2.0 * (10 + a));
    EXPECT_EQ(rho[a], 2.0 * (1000 + a));
  }
  // and the other way: a view write is what the N_Vector holds
  x(2, 3) = -7.0;
  EXPECT_EQ(NV_Ith_S(v, static_cast<sunindextype>(L.offset(Field::Position) + 3 * 3 + 2)), -7.0);
  N_VDestroy(v);
  SUNContext_Free(&ctx);
}

TEST(StateLayout, SpeciesFollowEachOtherAndKeepTheirOwnFields) {
  StateLayout L(4);
  L.add(Field::Position, 3).add(Field::Velocity, 3);
  L.add_species(Species::Sink, 2).add(Field::Position, 3).add(Field::Velocity, 3).add(Field::Mass, 1).add(Field::Spin, 3);
  EXPECT_EQ(L.particles(), 4u);
  EXPECT_EQ(L.particles(Species::Sink), 2u);
  EXPECT_EQ(L.offset(Field::Velocity), 12u);
  EXPECT_EQ(L.offset(Species::Sink, Field::Position), 24u);
  EXPECT_EQ(L.offset(Species::Sink, Field::Mass), 36u);
  EXPECT_EQ(L.offset(Species::Sink, Field::Spin), 38u);
  EXPECT_EQ(L.size(), 44u);
  EXPECT_FALSE(L.has(Field::Mass));  // the gas has no mass field
  EXPECT_TRUE(L.has(Species::Sink, Field::Mass));
  EXPECT_EQ(L.fields(Species::Sink).size(), 4u);
  EXPECT_THROW(L.add_species(Species::Sink, 1), std::invalid_argument);
  // a field added to the gas later moves the sinks behind it
  L.add(Species::Gas, Field::Density, 1);
  EXPECT_EQ(L.offset(Species::Sink, Field::Position), 28u);
  EXPECT_EQ(L.size(), 48u);
}

TEST(StateLayout, AFieldOfTheScenesOwnNeedsNoEditHere) {
  constexpr Field dust_fraction{"dust_fraction"};
  StateLayout L(3);
  L.add(Field::Position, 2).add(dust_fraction, 1);
  EXPECT_EQ(L.offset(dust_fraction), 6u);
  EXPECT_EQ(field_name(L.fields().back()), "dust_fraction");
  EXPECT_TRUE(L.has(Field{"dust_fraction"}));  // identified by name
}

TEST(StateLayout, ResizeKeepsEverySurvivorBitForBitAndLeavesNewParticlesZero) {
  StateLayout L(5);
  L.add(Field::Position, 2).add(Field::Density, 1);
  L.add_species(Species::Sink, 1).add(Field::Position, 2).add(Field::Mass, 1);
  std::vector<Real> y(L.size());
  for (std::size_t k = 0; k < y.size(); ++k) y[k] = std::ldexp(1.0 + 1e-3 * static_cast<Real>(k), static_cast<int>(k) % 7) / 3.0;
  // gas particles 1 and 3 are accreted: 3 survive, in the order 0, 2, 4
  const StateLayout gas_shrunk = L.with_count(Species::Gas, 3);
  const std::vector<Real> g = resize_species(L, y.data(), gas_shrunk, Species::Gas, {0, 2, 4});
  ASSERT_EQ(g.size(), gas_shrunk.size());
  const std::size_t kept[3] = {0, 2, 4};
  for (std::size_t i = 0; i < 3; ++i) {
    for (int c = 0; c < 2; ++c) EXPECT_EQ(g[2 * i + c], y[2 * kept[i] + c]);
    EXPECT_EQ(g[gas_shrunk.offset(Field::Density) + i], y[L.offset(Field::Density) + kept[i]]);
  }
  for (std::size_t k = 0; k < 3; ++k)  // the sink block, moved up but unchanged
    EXPECT_EQ(g[gas_shrunk.offset(Species::Sink, Field::Position) + k], y[L.offset(Species::Sink, Field::Position) + k]);
  // a second sink is created: the first keeps its values, the new one is zero
  const StateLayout more = gas_shrunk.with_count(Species::Sink, 2);
  const std::vector<Real> s = resize_species(gas_shrunk, g.data(), more, Species::Sink, {0});
  EXPECT_EQ(s[more.offset(Species::Sink, Field::Mass)], g[gas_shrunk.offset(Species::Sink, Field::Mass)]);
  EXPECT_EQ(s[more.offset(Species::Sink, Field::Mass) + 1], 0.0);
  EXPECT_EQ(s[more.offset(Species::Sink, Field::Position) + 2], 0.0);
  EXPECT_THROW(resize_species(L, y.data(), more, Species::Sink, {0}), std::invalid_argument);  // gas differs too
  EXPECT_THROW(resize_species(L, y.data(), gas_shrunk, Species::Gas, {0, 2, 5}), std::invalid_argument);
  // entry_sources: where each entry of the resized state came from, none for the new sink's
  const std::vector<std::size_t> from_gas = entry_sources(L, gas_shrunk, Species::Gas, {0, 2, 4});
  ASSERT_EQ(from_gas.size(), g.size());
  for (std::size_t k = 0; k < g.size(); ++k) EXPECT_EQ(g[k], y[from_gas[k]]) << k;
  const std::vector<std::size_t> from_sinks = entry_sources(gas_shrunk, more, Species::Sink, {0});
  ASSERT_EQ(from_sinks.size(), s.size());
  for (std::size_t k = 0; k < s.size(); ++k) {
    const bool new_sink = k == more.offset(Species::Sink, Field::Mass) + 1 ||
                          (k >= more.offset(Species::Sink, Field::Position) + 2 && k < more.offset(Species::Sink, Field::Position) + 4);
    if (new_sink)
      EXPECT_EQ(from_sinks[k], kNoEntrySource) << k;
    else
      EXPECT_EQ(s[k], g[from_sinks[k]]) << k;
  }
}
