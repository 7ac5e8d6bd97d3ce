#pragma once
// Shared helpers of the gravity tests: run a solver, compare fields, momentum error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sphark/gravity/force_errors.hpp"
#include "sphark/gravity/self_gravity.hpp"
#include "sphark/kernels/kernels.hpp"

namespace sphark::gravity_test {

// Every 3D kernel the gravity module supports, for typed tests.
using AllKernels = ::testing::Types<CubicSpline<3>, QuinticSpline<3>, WendlandC2<3>, WendlandC4<3>, WendlandC6<3>>;

struct Field {
  std::vector<Real> acc, pot;
  Real energy = 0;
};

template <class K = CubicSpline<3>>
Field solve(GravitySolver solver, const GravitySources& src, const GravityOptions& opt = {}) {
  Field f;
  f.acc.resize(3 * src.n);
  f.pot.resize(src.n);
  f.energy = make_self_gravity<K>(solver, opt)->compute(src, f.acc.data(), f.pot.data());
  return f;
}

// |a_test - a_ref| / |a_ref| per particle.
inline std::vector<Real> relative_force_errors(const Field& test, const Field& ref) {
  return sphark::relative_force_errors(test.acc.data(), ref.acc.data(), ref.pot.size());
}

// |sum_a m_a a_a| / sum_a |m_a a_a|
inline Real momentum_error(const std::vector<Real>& m, const std::vector<Real>& acc) {
  Real p[3] = {0, 0, 0}, scale = 0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    Real f2 = 0;
    for (int c = 0; c < 3; ++c) {
      p[c] += m[i] * acc[3 * i + c];
      f2 += m[i] * acc[3 * i + c] * m[i] * acc[3 * i + c];
    }
    scale += std::sqrt(f2);
  }
  return std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) / scale;
}

}  // namespace sphark::gravity_test
