#pragma once
// StateLayout: which fields a scene evolves and where each lives inside the ONE state vector
// that ARKODE advances. Fields are stored field-major: all particles' x, then all v, then rho...
// Inside a vector field the components of one particle are contiguous, so a field is an
// Eigen (components x N) column-major matrix and a particle is one column.
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "sphark/core/types.hpp"

namespace sphark {

enum class Field : int {
  Position = 0,
  Velocity,
  Density,
  InternalEnergy,
  MagneticField,
  Psi,
  EulerAlpha,
  EulerBeta,
  Count
};

std::string_view field_name(Field f);

class StateLayout {
 public:
  explicit StateLayout(std::size_t particles) : n_(particles) { offsets_.fill(kAbsent); comps_.fill(0); }

  // Appends a field with `components` values per particle. Each field can be added once.
  StateLayout& add(Field f, int components);

  bool has(Field f) const { return offsets_[idx(f)] != kAbsent; }
  std::size_t offset(Field f) const;            // throws std::out_of_range if absent
  int components(Field f) const { return comps_[idx(f)]; }
  std::size_t field_size(Field f) const { return n_ * static_cast<std::size_t>(components(f)); }
  std::size_t particles() const { return n_; }
  std::size_t size() const { return size_; }
  const std::vector<Field>& fields() const { return order_; }

 private:
  static constexpr std::size_t kAbsent = static_cast<std::size_t>(-1);
  static std::size_t idx(Field f) { return static_cast<std::size_t>(f); }
  std::size_t n_;
  std::size_t size_ = 0;
  std::array<std::size_t, static_cast<std::size_t>(Field::Count)> offsets_;
  std::array<int, static_cast<std::size_t>(Field::Count)> comps_;
  std::vector<Field> order_;
};

// Zero-copy views over a raw state array (ARKODE's N_Vector data or our own buffer).
template <int C>
using FieldMap = Eigen::Map<Eigen::Matrix<Real, C, Eigen::Dynamic>>;
template <int C>
using ConstFieldMap = Eigen::Map<const Eigen::Matrix<Real, C, Eigen::Dynamic>>;
using ScalarMap = Eigen::Map<Eigen::Matrix<Real, Eigen::Dynamic, 1>>;
using ConstScalarMap = Eigen::Map<const Eigen::Matrix<Real, Eigen::Dynamic, 1>>;

template <int C>
FieldMap<C> vector_field(Real* y, const StateLayout& L, Field f) {
  if (L.components(f) != C) throw std::logic_error("vector_field: wrong component count for " + std::string(field_name(f)));
  return FieldMap<C>(y + L.offset(f), C, static_cast<Index>(L.particles()));
}
template <int C>
ConstFieldMap<C> vector_field(const Real* y, const StateLayout& L, Field f) {
  if (L.components(f) != C) throw std::logic_error("vector_field: wrong component count for " + std::string(field_name(f)));
  return ConstFieldMap<C>(y + L.offset(f), C, static_cast<Index>(L.particles()));
}
inline ScalarMap scalar_field(Real* y, const StateLayout& L, Field f) {
  if (L.components(f) != 1) throw std::logic_error("scalar_field: not a scalar: " + std::string(field_name(f)));
  return ScalarMap(y + L.offset(f), static_cast<Index>(L.particles()));
}
inline ConstScalarMap scalar_field(const Real* y, const StateLayout& L, Field f) {
  if (L.components(f) != 1) throw std::logic_error("scalar_field: not a scalar: " + std::string(field_name(f)));
  return ConstScalarMap(y + L.offset(f), static_cast<Index>(L.particles()));
}

// Per-entry absolute tolerances from one value per field (fields not named use `fallback`).
std::vector<Real> per_field_tolerance(const StateLayout& L, const std::vector<std::pair<Field, Real>>& atol,
                                      Real fallback);

}  // namespace sphark
