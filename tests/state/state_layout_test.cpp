// StateLayout offsets and the zero-copy path between our state array, its Eigen views and a
// SUNDIALS serial N_Vector wrapping the same memory (what the ARKODE steppers hand to the RHS).
#include <gtest/gtest.h>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

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
