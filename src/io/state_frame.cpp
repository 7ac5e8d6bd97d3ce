#include "sphark/io/state_frame.hpp"

#include <stdexcept>
#include <string>

namespace sphark {

ParticleFrame frame_from_state(const StateLayout& layout, const Real* y) {
  if (!layout.has(Field::Position)) {
    throw std::invalid_argument("frame_from_state: the layout has no position field");
  }
  ParticleFrame f;
  f.dim = layout.components(Field::Position);
  if (f.dim < 1 || f.dim > 3) {
    throw std::invalid_argument("frame_from_state: position has " + std::to_string(f.dim) +
                                " components (1..3)");
  }
  f.count = layout.particles();
  f.positions = y + layout.offset(Field::Position);
  for (Field field : layout.fields()) {
    if (field == Field::Position) continue;
    const int c = layout.components(field);
    if (c > 3) {
      throw std::invalid_argument("frame_from_state: " + std::string(field_name(field)) +
                                  " has " + std::to_string(c) + " components (at most 3)");
    }
    f.arrays.push_back({std::string(field_name(field)), y + layout.offset(field), c});
  }
  return f;
}

}  // namespace sphark
