#pragma once
// Basic numeric types shared by every module.
#include <Eigen/Core>
#include <cstddef>

namespace sphark {

using Real = double;
using Index = std::ptrdiff_t;

template <int D>
using Vec = Eigen::Matrix<Real, D, 1>;

inline constexpr Real kPi = 3.14159265358979323846264338327950288;

}  // namespace sphark
