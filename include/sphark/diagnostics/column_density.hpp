#pragma once
// Column density maps of 3D particles: Sigma(X, Y) = int rho dz along one axis, the SPH estimate
//   Sigma(R) = sum_b m_b F(|R - R_b| / h_b) / h_b^2,   F(q) = int W~(sqrt(q^2 + s^2)) ds
// (W(r, h) = W~(r / h) / h^3: the kernel integrated through the particle; int F 2 pi q dq = 1),
// sampled at pixel centres. A particle smaller than a pixel is widened to h = pixel / 2 (so that
// its support always covers a pixel centre). A particle whose support spans at most 16 pixels has
// its pixel weights normalised to its mass (the map holds its mass exactly, to round-off, when its
// support lies inside); a wider one carries the analytic weight m F(q) / h^2 on the image's pixels
// only (its mass within the pixel sum's midpoint error, < 1e-4). Figure 4 of seed 000 is this map
// along y.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/kernels/kernels.hpp"

namespace sphark {

struct ColumnDensityMap {
  int axis = 1;              // projected along x (0), y (1) or z (2); the image axes are the other two in order
  int nx = 0, ny = 0;        // pixels along the image axes
  Real x0 = 0, x1 = 0;       // image extent along the first image axis
  Real y0 = 0, y1 = 0;       // and the second
  std::vector<Real> sigma;   // ny rows of nx values (row j: y0 + (j + 1/2) dy), mass per area
  Real pixel_area() const { return (x1 - x0) / nx * ((y1 - y0) / ny); }
};

// The column kernel F(q) of kernel K (3D), tabulated once (q in [0, support]) and interpolated.
template <class K = CubicSpline<3>>
Real column_kernel(Real q);

// n particles, x 3 x n column-major, masses m, smoothing lengths h. The image spans
// [x0, x1] x [y0, y1] with nx x ny pixels. Throws std::invalid_argument for an empty extent,
// no pixels or a bad axis. `stop`, polled every 64 particles, abandons the map by throwing
// ColumnDensityStopped when it returns true (a stop signal during the run's last products).
struct ColumnDensityStopped {};
template <class K = CubicSpline<3>>
ColumnDensityMap column_density(const Real* x, const Real* m, const Real* h, std::size_t n, int axis, Real x0, Real x1,
                                Real y0, Real y1, int nx, int ny, const std::function<bool()>& stop = {});

// Writes the map as text: a first line with the values axis,nx,ny,x0,x1,y0,y1, then ny lines of nx values
// (%.6e). Atomically (io/atomic_file.hpp).
void write_column_density(const std::string& path, const ColumnDensityMap& map);

}  // namespace sphark
