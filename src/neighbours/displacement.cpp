#include "sphark/neighbours/displacement.hpp"

#include <algorithm>
#include <cmath>

namespace sphark {

namespace {

// Squared distance particle i (stored at order[i]) has moved since the reference positions.
template <int D>
Real squared_displacement(const Real* x, const Real* ref, std::size_t i, const std::optional<PeriodicBox<D>>& box,
                          const std::uint32_t* order) {
  const std::size_t p = order ? order[i] : i;
  Vec<D> d = Eigen::Map<const Vec<D>>(x + D * p) - Eigen::Map<const Vec<D>>(ref + D * i);
  if (box) d = box->minimum_image(d);
  return d.squaredNorm();
}

}  // namespace

template <int D>
Real max_displacement(const Real* x, const Real* ref, std::size_t n, const std::optional<PeriodicBox<D>>& box,
                      const std::uint32_t* order) {
  Real m2 = 0;
#pragma omp parallel for reduction(max : m2) schedule(static)
  for (std::size_t i = 0; i < n; ++i) m2 = std::max(m2, squared_displacement<D>(x, ref, i, box, order));
  return std::sqrt(m2);
}

template <int D>
void displacements(const Real* x, const Real* ref, std::size_t n, const std::optional<PeriodicBox<D>>& box,
                   std::vector<Real>& out, const std::uint32_t* order) {
  out.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) out[i] = std::sqrt(squared_displacement<D>(x, ref, i, box, order));
}

template void displacements<1>(const Real*, const Real*, std::size_t, const std::optional<PeriodicBox<1>>&,
                               std::vector<Real>&, const std::uint32_t*);
template void displacements<2>(const Real*, const Real*, std::size_t, const std::optional<PeriodicBox<2>>&,
                               std::vector<Real>&, const std::uint32_t*);
template void displacements<3>(const Real*, const Real*, std::size_t, const std::optional<PeriodicBox<3>>&,
                               std::vector<Real>&, const std::uint32_t*);

template Real max_displacement<1>(const Real*, const Real*, std::size_t, const std::optional<PeriodicBox<1>>&,
                                  const std::uint32_t*);
template Real max_displacement<2>(const Real*, const Real*, std::size_t, const std::optional<PeriodicBox<2>>&,
                                  const std::uint32_t*);
template Real max_displacement<3>(const Real*, const Real*, std::size_t, const std::optional<PeriodicBox<3>>&,
                                  const std::uint32_t*);

}  // namespace sphark
