#pragma once
// A ParticleFrame viewing a state vector in place (no copies): positions from Field::Position
// (its component count is the dimension), and every other field of the layout as a point
// array named field_name(f) ("velocity", "density", "psi", ...). The layout is field-major
// with the components of one particle contiguous, which is exactly ParticleFrame's
// point-major layout. Derived arrays (pressure, div_v, ...) are appended by the caller:
//   ParticleFrame f = frame_from_state(layout, y);
//   f.arrays.push_back({"pressure", pressure.data(), 1});
#include "sphark/io/particle_frame.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark {

// Throws std::invalid_argument if the layout has no Position field, Position has not 1..3
// components, or another field has more than 3 components.
ParticleFrame frame_from_state(const StateLayout& layout, const Real* y);

}  // namespace sphark
