#pragma once
// A snapshot of particle data handed to writers: positions plus named point arrays.
// The arrays are views (no copies); the caller keeps the data alive during write().
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark {

struct PointArray {
  std::string name;     // with its meaning: "density", "velocity", "pressure", "div_v", "psi", ...
  const Real* data;     // components values per point, point-major (x0 y0 z0 x1 y1 z1 ...)
  int components;       // 1 (scalar), or 2/3 (vectors: written as 3-component in VTK)
};

struct ParticleFrame {
  int dim = 2;                     // 1, 2 or 3
  std::size_t count = 0;           // number of points
  const Real* positions = nullptr; // dim values per point, point-major
  std::vector<PointArray> arrays;
  const std::int64_t* ids = nullptr;  // optional global particle ids: written as the Int64 array "id"
};

}  // namespace sphark
