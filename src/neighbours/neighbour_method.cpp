#include "sphark/neighbours/neighbour_method.hpp"

#include <algorithm>

namespace sphark {

Real cell_grid_overhead(const Real* radii, std::size_t n, Real r_max, int dim) {
  if (!radii || n == 0) return 1;
  Real sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Real q = r_max / std::min(radii[i], r_max);
    sum += dim == 1 ? q : dim == 2 ? q * q : q * q * q;
  }
  return sum / static_cast<Real>(n);
}

}  // namespace sphark
