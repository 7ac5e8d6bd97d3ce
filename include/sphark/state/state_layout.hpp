#pragma once
// StateLayout: which particle species a scene evolves, which fields each species carries, and
// where every value lives inside the ONE state vector that ARKODE advances.
//
// The model is open: a Field or a Species is a named constant, and a scene may define its own
// (`inline constexpr Field kSpin{"spin"};`) without editing this file. The well-known ones are
// Field::Position, Field::Velocity, ... and Species::Gas, Species::Sink.
//
// Memory order: species after species (in the order they were added); inside a species field
// after field (all its particles' x, then all v, ...); inside a vector field the components of
// one particle are contiguous, so a field is an Eigen (components x N) column-major matrix and a
// particle is one column. A species' particle count may change between steps: with_count()
// gives the resized layout and resize_species() carries the surviving particles over.
//
// Queries without a Species refer to the first species (the gas in every scene).
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "sphark/core/types.hpp"

namespace sphark {

// A per-particle field, identified by its name (which is also its name in checkpoints and VTK).
class Field {
 public:
  constexpr explicit Field(std::string_view name) : name_(name) {}
  constexpr std::string_view name() const { return name_; }
  constexpr bool operator==(const Field& o) const { return name_ == o.name_; }

  static const Field Position, Velocity, Density, InternalEnergy, MagneticField, Psi, EulerAlpha, Mass, Spin;

 private:
  std::string_view name_;
};
inline constexpr Field Field::Position{"position"};
inline constexpr Field Field::Velocity{"velocity"};
inline constexpr Field Field::Density{"density"};
inline constexpr Field Field::InternalEnergy{"internal_energy"};
inline constexpr Field Field::MagneticField{"magnetic_field"};
inline constexpr Field Field::Psi{"psi"};
inline constexpr Field Field::EulerAlpha{"euler_alpha"};
inline constexpr Field Field::Mass{"mass"};
inline constexpr Field Field::Spin{"spin"};

inline std::string_view field_name(Field f) { return f.name(); }

// A kind of particle with its own fields and count (gas; sink particles; ...).
class Species {
 public:
  constexpr explicit Species(std::string_view name) : name_(name) {}
  constexpr std::string_view name() const { return name_; }
  constexpr bool operator==(const Species& o) const { return name_ == o.name_; }

  static const Species Gas, Sink;

 private:
  std::string_view name_;
};
inline constexpr Species Species::Gas{"gas"};
inline constexpr Species Species::Sink{"sink"};

class StateLayout {
 public:
  struct FieldSlot {
    Field field;
    int components;
    std::size_t offset;  // of the field's first value in the state vector
  };
  struct SpeciesBlock {
    Species species;
    std::size_t count;
    std::size_t offset;  // of the species' first value in the state vector
    std::vector<FieldSlot> fields;
  };

  StateLayout() = default;
  // One species, the gas, with `particles` particles (fields added with add()).
  explicit StateLayout(std::size_t particles) { add_species(Species::Gas, particles); }

  // Appends a species with `count` particles; each species can be added once.
  StateLayout& add_species(Species s, std::size_t count);
  // Appends a field with `components` values per particle to the most recently added species
  // (or to species s); each field can be added once per species.
  StateLayout& add(Field f, int components);
  StateLayout& add(Species s, Field f, int components);

  bool has(Species s) const { return find(s) != nullptr; }
  bool has(Field f) const { return !blocks_.empty() && has(primary(), f); }
  bool has(Species s, Field f) const;
  // Offset of the field's first value; throws std::out_of_range naming what is absent.
  std::size_t offset(Field f) const { return offset(primary(), f); }
  std::size_t offset(Species s, Field f) const { return slot(s, f).offset; }
  int components(Field f) const { return has(f) ? slot(primary(), f).components : 0; }
  int components(Species s, Field f) const { return has(s, f) ? slot(s, f).components : 0; }
  std::size_t field_size(Field f) const { return field_size(primary(), f); }
  std::size_t field_size(Species s, Field f) const;
  // Particles of the first species (0 for an empty layout) / of species s (0 if absent).
  std::size_t particles() const { return blocks_.empty() ? 0 : blocks_.front().count; }
  std::size_t particles(Species s) const;
  std::size_t size() const { return size_; }
  // Fields of the first species / of species s, in state order.
  std::vector<Field> fields() const;
  std::vector<Field> fields(Species s) const;
  const std::vector<SpeciesBlock>& species() const { return blocks_; }

  // The same layout with species s holding `count` particles (offsets recomputed).
  StateLayout with_count(Species s, std::size_t count) const;

  bool operator==(const StateLayout& o) const;

  // The first species (std::out_of_range for an empty layout).
  Species primary() const;

 private:
  const SpeciesBlock* find(Species s) const;
  SpeciesBlock& block(Species s);
  const FieldSlot& slot(Species s, Field f) const;
  void relayout();

  std::vector<SpeciesBlock> blocks_;
  std::size_t size_ = 0;
};

// The state y_from (laid out by `from`) carried over to layout `to`, which differs from `from`
// only in the count of species s: particle i of s in `to` is particle keep[i] of s in `from`
// for i < keep.size(); the particles after them (to.particles(s) - keep.size() of them, e.g.
// newly created sinks) are zero for the caller to fill. Every other species is copied as it is.
// Every copied value is bit for bit the old one. Throws std::invalid_argument for layouts that
// differ otherwise, an index out of range or keep longer than the new count.
std::vector<Real> resize_species(const StateLayout& from, const Real* y_from, const StateLayout& to, Species s,
                                 const std::vector<std::size_t>& keep);

// For each entry of `to` (resize_species(from, ., to, s, keep)), the entry of `from` it copies;
// kNoEntrySource for the entries of the particles after keep.
inline constexpr std::size_t kNoEntrySource = ~std::size_t{0};
std::vector<std::size_t> entry_sources(const StateLayout& from, const StateLayout& to, Species s,
                                       const std::vector<std::size_t>& keep);
// Zero-copy views over a raw state array (ARKODE's N_Vector data or our own buffer).
template <int C>
using FieldMap = Eigen::Map<Eigen::Matrix<Real, C, Eigen::Dynamic>>;
template <int C>
using ConstFieldMap = Eigen::Map<const Eigen::Matrix<Real, C, Eigen::Dynamic>>;
using ScalarMap = Eigen::Map<Eigen::Matrix<Real, Eigen::Dynamic, 1>>;
using ConstScalarMap = Eigen::Map<const Eigen::Matrix<Real, Eigen::Dynamic, 1>>;

namespace state_detail {
[[noreturn]] void wrong_components(Field f, int expected, int actual);
}  // namespace state_detail

template <int C>
FieldMap<C> vector_field(Real* y, const StateLayout& L, Field f, Species s) {
  if (L.components(s, f) != C) state_detail::wrong_components(f, C, L.components(s, f));
  return FieldMap<C>(y + L.offset(s, f), C, static_cast<Index>(L.particles(s)));
}
template <int C>
ConstFieldMap<C> vector_field(const Real* y, const StateLayout& L, Field f, Species s) {
  if (L.components(s, f) != C) state_detail::wrong_components(f, C, L.components(s, f));
  return ConstFieldMap<C>(y + L.offset(s, f), C, static_cast<Index>(L.particles(s)));
}
inline ScalarMap scalar_field(Real* y, const StateLayout& L, Field f, Species s) {
  if (L.components(s, f) != 1) state_detail::wrong_components(f, 1, L.components(s, f));
  return ScalarMap(y + L.offset(s, f), static_cast<Index>(L.particles(s)));
}
inline ConstScalarMap scalar_field(const Real* y, const StateLayout& L, Field f, Species s) {
  if (L.components(s, f) != 1) state_detail::wrong_components(f, 1, L.components(s, f));
  return ConstScalarMap(y + L.offset(s, f), static_cast<Index>(L.particles(s)));
}
// The same for the first species.
template <int C>
FieldMap<C> vector_field(Real* y, const StateLayout& L, Field f) { return vector_field<C>(y, L, f, L.primary()); }
template <int C>
ConstFieldMap<C> vector_field(const Real* y, const StateLayout& L, Field f) {
  return vector_field<C>(y, L, f, L.primary());
}
inline ScalarMap scalar_field(Real* y, const StateLayout& L, Field f) { return scalar_field(y, L, f, L.primary()); }
inline ConstScalarMap scalar_field(const Real* y, const StateLayout& L, Field f) {
  return scalar_field(y, L, f, L.primary());
}

// Per-entry absolute tolerances from one value per field of the first species (entries of
// fields not named, and of other species, get `fallback`).
std::vector<Real> per_field_tolerance(const StateLayout& L, const std::vector<std::pair<Field, Real>>& atol,
                                      Real fallback);

}  // namespace sphark
