// Exact kernel properties: normalisation (zeroth moment = 1), vanishing first moment,
// compact support, and dW/dr against central finite differences, for every kernel in 1-3D.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "sphark/kernels/kernel_list.hpp"

using namespace sphark;

namespace {
// Integral of g(r) over R^D for radial g, using the surface measure of the unit sphere.
template <int D, class G>
Real radial_integral(G g, Real rmax) {
  const Real surface = D == 1 ? 2.0 : D == 2 ? 2.0 * kPi : 4.0 * kPi;
  const int n = 20000;  // composite Simpson: kernels are piecewise polynomials, error ~1e-13
  const Real dr = rmax / n;
  Real s = 0;
  for (int i = 0; i <= n; ++i) {
    const Real r = i * dr;
    const Real wgt = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    s += wgt * g(r) * std::pow(r, D - 1);
  }
  return surface * s * dr / 3.0;
}

template <class K, int D>
void check_kernel() {
  const Real h = 0.37;
  const Real rmax = K::support * h;
  SCOPED_TRACE(std::string(K::name) + " D=" + std::to_string(D));
  EXPECT_NEAR(radial_integral<D>([&](Real r) { return K::w(r, h); }, rmax), 1.0, 1e-10);
  // second moment of a symmetric kernel is finite and positive; first moment vanishes by symmetry
  EXPECT_EQ(K::w(rmax * 1.0000001, h), 0.0);
  EXPECT_EQ(K::dw_dr(rmax * 1.0000001, h), 0.0);
  for (Real q : {0.05, 0.3, 0.77, 0.999, 1.001, 1.4, 1.9, 2.5}) {
    const Real r = q * h;
    if (r >= rmax) continue;
    const Real eps = 1e-6 * h;
    const Real fd = (K::w(r + eps, h) - K::w(r - eps, h)) / (2 * eps);
    EXPECT_NEAR(K::dw_dr(r, h), fd, 1e-6 * std::abs(K::w(0, h)) / h) << "q=" << q;
    EXPECT_NEAR(K::f_over_r(r, h), K::dw_dr(r, h) / r, 1e-10 * std::abs(K::w(0, h)) / (h * h)) << "q=" << q;
  }
  EXPECT_TRUE(std::isfinite(K::f_over_r(0.0, h)));
  EXPECT_LT(K::f_over_r(0.0, h), 0.0);
}
}  // namespace

template <int D, class... K>
void check_kernels(KernelTypes<K...>) {
  (check_kernel<K, D>(), ...);
}

TEST(Kernels, NormalisedWithCompactSupportAndConsistentDerivative) {
  check_kernels<1>(KernelList<1>{});
  check_kernels<2>(KernelList<2>{});
  check_kernels<3>(KernelList<3>{});
}

// The run-time choice by name reaches every kernel of the list, each under its own name, and
// rejects an unknown name with the list of known ones.
TEST(KernelList, EveryNameSelectsItsKernel) {
  const std::vector<std::string> names = kernel_names<2>();
  ASSERT_EQ(names.size(), KernelList<2>::size);
  for (const std::string& name : names) {
    EXPECT_EQ(std::count(names.begin(), names.end(), name), 1) << name;
    const std::string_view chosen = with_kernel<2>(name, [](auto tag) { return decltype(tag)::type::name; });
    EXPECT_EQ(chosen, name);
  }
  EXPECT_EQ(kernel_names<3>(), names);
  EXPECT_TRUE(with_kernel<2>("cubic", [](auto tag) { return std::is_same_v<typename decltype(tag)::type, CubicSpline<2>>; }));
  EXPECT_TRUE(
      with_kernel<3>("wendland_c4", [](auto tag) { return std::is_same_v<typename decltype(tag)::type, WendlandC4<3>>; }));
  try {
    with_kernel<2>("no_such_kernel", [](auto) { return 0; });
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_kernel"), std::string::npos);
    for (const std::string& name : names) EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << name;
  }
}

// The branch-free unit-h forms of the pair loops' lanes (kernels.hpp) equal the kernels at h = 1
// to round-off, on one lane and on two (simd::Real2), inside the support and beyond (exact 0).
// Round-off: the spline forms add clamped powers that cancel, at worst (the quintic at q -> 0)
// (3^5 + 6 2^5 + 15) / 66 = 6.8 times the value, so the bound is 32 eps of the kernel's scale;
// f'/q divides such a sum by q (the quintic, as kernels.hpp's own form): 32 eps / min(q, 1).
namespace {
template <class K, int D>
void check_unit_forms() {
  constexpr Real tol = 32 * 2.220446049250313e-16;
  const Real w0 = std::abs(K::w(0, 1.0)), f0 = std::abs(K::f_over_r(0, 1.0));
  for (int i = 1; i <= 400; ++i) {
    const Real q = 0.00875 * i;  // 0.00875 .. 3.5
    EXPECT_NEAR(K::unit_w(q), K::w(q, 1.0), tol * w0) << K::name << " q=" << q;
    EXPECT_NEAR(K::unit_q_dw(q), q * q * K::f_over_r(q, 1.0), tol * f0) << K::name << " q=" << q;
    EXPECT_NEAR(K::unit_f_over_r(q, 1 / q), K::f_over_r(q, 1.0), tol * f0 / std::min(q, 1.0)) << K::name << " q=" << q;
    const simd::Real2 qq{q, q + 0.001};
    const simd::Real2 w = K::unit_w(qq), f = K::unit_f_over_r(qq, 1.0 / qq);
    EXPECT_EQ(w[0], K::unit_w(q));
    EXPECT_EQ(f[1], K::unit_f_over_r(q + 0.001, 1 / (q + 0.001)));
    if (q >= K::support) {
      EXPECT_EQ(K::unit_w(q), 0.0);
      EXPECT_EQ(K::unit_f_over_r(q, 1 / q), 0.0);
    }
  }
}
template <int D, class... K>
void check_unit_forms_of(KernelTypes<K...>) {
  (check_unit_forms<K, D>(), ...);
}
}  // namespace

TEST(Kernels, UnitFormsForLanesEqualTheKernels) {
  check_unit_forms_of<1>(KernelList<1>{});
  check_unit_forms_of<2>(KernelList<2>{});
  check_unit_forms_of<3>(KernelList<3>{});
}
