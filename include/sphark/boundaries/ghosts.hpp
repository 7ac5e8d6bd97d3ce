#pragma once
// Ghost particles across a wall (seed 004, §2, approach C): every fluid particle with
// -width < s <= 0 gets a ghost at s' = psi(s) on its own normal line (u, v unchanged, seed 004
// eq. 9), with the same mass and scalars (gather_scalar) and its velocity with the normal
// component reversed (free slip) or fully reversed (no slip).
//
// GhostLayer keeps its buffers between calls: after the first call with n particles, later calls
// with at most as many particles do not allocate (clear() keeps the capacity), so a scheme can
// regenerate ghosts inside every right-hand-side evaluation. With a periodic box the wall is
// found through the minimum image and the ghost is wrapped back into the box.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sphark/boundaries/walls.hpp"
#include "sphark/neighbours/periodic_box.hpp"

namespace sphark {

enum class GhostMap { Mirror, DensityPreserving };
enum class VelocityBc { FreeSlip, NoSlip };
enum class OnInvalid { Throw, Skip };

struct GhostOptions {
  Real width = 0;  // layer thickness: particles with s > -width get a ghost (the kernel support H)
  GhostMap map = GhostMap::DensityPreserving;
  VelocityBc velocity = VelocityBc::FreeSlip;
  OnInvalid on_invalid = OnInvalid::Throw;  // Skip: leave the particle without ghost, report it
};

// What one append() did. `invalid` counts particles whose map left its valid range (the first
// one is described); `outside` counts particles found on the wall's far side (s > 0).
struct GhostReport {
  std::size_t generated = 0;
  std::size_t invalid = 0;
  std::size_t outside = 0;
  std::size_t first_invalid = 0;
  Real first_invalid_s = 0;
  Real first_invalid_cos_u = 0;
  MapStatus first_status = MapStatus::Ok;
  std::string message() const;  // one line; empty when invalid == 0
};

template <int D>
class GhostLayer {
 public:
  // Append the ghosts of particles x (D x n, point-major) across `wall`; v may be null.
  // Throws std::domain_error (after placing the valid ghosts) if a map left its valid range and
  // opt.on_invalid == Throw.
  GhostReport append(const Wall<D>& wall, const Real* x, const Real* v, std::size_t n,
                     const GhostOptions& opt, const PeriodicBox<D>* box = nullptr);

  void clear() { count_ = 0; }
  void reserve(std::size_t n);
  std::size_t size() const { return count_; }
  std::size_t capacity() const { return src_.size(); }

  const Real* positions() const { return x_.data(); }   // D per ghost
  const Real* velocities() const { return v_.data(); }  // D per ghost (zero if v was null)
  const Real* wall_s() const { return s_.data(); }      // s' of each ghost (>= 0)
  const std::uint32_t* sources() const { return src_.data(); }  // index of the inner particle

  // out[g] = field[source[g]] (mass, density, pressure, internal energy, ...).
  void gather_scalar(const Real* field, Real* out) const {
    for (std::size_t g = 0; g < count_; ++g) out[g] = field[src_[g]];
  }

 private:
  std::vector<Real> x_, v_, s_;
  std::vector<std::uint32_t> src_;
  std::size_t count_ = 0;
};

extern template class GhostLayer<2>;
extern template class GhostLayer<3>;

}  // namespace sphark
