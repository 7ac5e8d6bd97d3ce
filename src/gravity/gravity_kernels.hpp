#pragma once
// The kernels the gravity module is instantiated for (every 3D kernel of kernels.hpp):
// SPHARK_GRAVITY_KERNELS(X) expands X(K) for each.
#include "sphark/kernels/kernels.hpp"

#define SPHARK_GRAVITY_KERNELS(X) \
  X(CubicSpline<3>)               \
  X(QuinticSpline<3>)             \
  X(WendlandC2<3>)                \
  X(WendlandC4<3>)                \
  X(WendlandC6<3>)
