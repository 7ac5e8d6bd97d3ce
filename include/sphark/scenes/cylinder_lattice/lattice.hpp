#pragma once
// Flow of a compressible liquid through a periodic lattice of cylinders (seed 004, §8): the
// 2D periodic box [-0.5, 0.5]^2 with a circular obstacle of radius R at the origin, ghost
// particles across its wall, a driving term dv_x/dt += (v0 - v_x)/tau (seed 004, eq. 36). The
// scheme is schemes/ghost_wcsph (grad-h WCSPH with ghost walls) with the Wendland C4 kernel
// (support H = 2h); the paper's §2 and its silences are documented in docs/cylinder_lattice.md.
#include <cstddef>

#include "sphark/kernels/kernels.hpp"
#include "sphark/schemes/ghost_wcsph/ghost_wcsph.hpp"

namespace sphark {

// The scene's parameters: the box and the obstacle, and the scheme's (GhostWcsphParams, whose
// defaults are this scene's: c_s = 5 = 10 x the medium-resolution v0 = 0.5, eta = 1.3, ...).
struct LatticeParams : GhostWcsphParams {
  Real half_box = 0.5;  // box [-half_box, half_box]^2, periodic in x and y
  Real radius = 0.2;    // obstacle radius R (centre at the origin)
};

// The uniform-lattice spacing of n particles in the fluid area (box minus disc).
Real lattice_spacing(const LatticeParams& p, std::size_t n);
// The box [-half_box, half_box]^2, periodic along x and y.
PeriodicBox<2> lattice_box(const LatticeParams& p);
// The obstacle's wall, fluid outside.
Wall<2> lattice_wall(const LatticeParams& p);

using LatticeKernel = WendlandC4<2>;

// The scheme on the lattice (throws std::invalid_argument for an obstacle that does not fit).
class LatticeSystem final : public GhostWcsph<LatticeKernel> {
 public:
  LatticeSystem(std::size_t particles, const LatticeParams& params);
  const LatticeParams& params() const { return lattice_; }

 private:
  LatticeParams lattice_;
};

}  // namespace sphark
