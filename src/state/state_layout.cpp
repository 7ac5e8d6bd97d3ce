#include "sphark/state/state_layout.hpp"

namespace sphark {

std::string_view field_name(Field f) {
  switch (f) {
    case Field::Position: return "position";
    case Field::Velocity: return "velocity";
    case Field::Density: return "density";
    case Field::InternalEnergy: return "internal_energy";
    case Field::MagneticField: return "magnetic_field";
    case Field::Psi: return "psi";
    case Field::EulerAlpha: return "euler_alpha";
    case Field::EulerBeta: return "euler_beta";
    case Field::Count: break;
  }
  return "unknown";
}

StateLayout& StateLayout::add(Field f, int components) {
  if (components <= 0) throw std::invalid_argument("StateLayout::add: components must be positive");
  if (has(f)) throw std::invalid_argument("StateLayout::add: field added twice: " + std::string(field_name(f)));
  offsets_[idx(f)] = size_;
  comps_[idx(f)] = components;
  size_ += n_ * static_cast<std::size_t>(components);
  order_.push_back(f);
  return *this;
}

std::size_t StateLayout::offset(Field f) const {
  if (!has(f)) throw std::out_of_range("StateLayout: field not in this state: " + std::string(field_name(f)));
  return offsets_[idx(f)];
}

std::vector<Real> per_field_tolerance(const StateLayout& L, const std::vector<std::pair<Field, Real>>& atol,
                                      Real fallback) {
  std::vector<Real> out(L.size(), fallback);
  for (const auto& [f, value] : atol) {
    if (!L.has(f)) continue;
    const std::size_t o = L.offset(f);
    for (std::size_t i = 0; i < L.field_size(f); ++i) out[o + i] = value;
  }
  return out;
}

}  // namespace sphark
