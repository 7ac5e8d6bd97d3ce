#pragma once
// Whether two vectors of reals are the same bit for bit (restart and repartition tests).
#include <cstring>
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark::test {

inline bool bit_equal(const std::vector<Real>& a, const std::vector<Real>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Real)) == 0;
}

}  // namespace sphark::test
