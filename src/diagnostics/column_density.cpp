#include "sphark/diagnostics/column_density.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "sphark/io/atomic_file.hpp"
#include "sphark/kernels/kernel_list.hpp"

namespace sphark {

namespace {

constexpr int kTable = 4096;  // intervals of the F(q) table on [0, support]

// int_a^b g(s) ds by 16 panels of 8-point Gauss-Legendre.
template <class G>
Real gauss_legendre(const G& g, Real a, Real b) {
  static constexpr std::array<Real, 4> node = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                               0.9602898564975363};
  static constexpr std::array<Real, 4> weight = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                                 0.1012285362903763};
  constexpr int panels = 16;
  const Real w = (b - a) / panels;
  Real sum = 0;
  for (int p = 0; p < panels; ++p) {
    const Real mid = a + (p + 0.5) * w, half = 0.5 * w;
    for (int k = 0; k < 4; ++k) sum += half * weight[k] * (g(mid - half * node[k]) + g(mid + half * node[k]));
  }
  return sum;
}

// F(q) = 2 int_0^{sqrt(Q^2 - q^2)} W~(sqrt(q^2 + s^2)) ds, split where sqrt(q^2 + s^2) crosses an
// integer (the kernels' polynomial pieces end at integer q).
template <class K>
Real column_kernel_exact(Real q) {
  const Real Q = K::support;
  if (q >= Q) return 0;
  const auto g = [q](Real s) { return K::w(std::sqrt(q * q + s * s), 1.0); };
  Real sum = 0, s_prev = 0;
  for (int k = static_cast<int>(std::floor(q)) + 1; k <= static_cast<int>(std::ceil(Q)); ++k) {
    const Real r = std::min<Real>(k, Q);
    const Real s = std::sqrt(std::max<Real>(0, r * r - q * q));
    if (s > s_prev) sum += gauss_legendre(g, s_prev, s);
    s_prev = s;
  }
  return 2 * sum;
}

template <class K>
const std::vector<Real>& column_table() {
  static const std::vector<Real> table = [] {
    std::vector<Real> t(kTable + 2, 0);
    for (int i = 0; i <= kTable; ++i) t[i] = column_kernel_exact<K>(K::support * i / kTable);
    return t;
  }();
  return table;
}

}  // namespace

template <class K>
Real column_kernel(Real q) {
  if (!(q < K::support)) return 0;
  const std::vector<Real>& t = column_table<K>();
  const Real u = q / K::support * kTable;
  const int i = static_cast<int>(u);
  const Real f = u - i;
  return (1 - f) * t[i] + f * t[i + 1];
}

namespace {
// A particle whose support spans more than this many pixels each way carries its analytic weight
// m F(q) / h^2 (int F 2 pi q dq = 1; the pixel sum's midpoint error is below 1e-4 of its mass, see
// the test) and is visited on the image's pixels only; a narrower one is normalised over every
// pixel centre of its support, the image's or not (mass exact to round-off).
constexpr Real kWidePixels = 16;

template <class K>
Real weight_at(const ColumnDensityMap& map, int i, int j, Real X, Real Y, Real inv_h, Real dx, Real dy) {
  const Real a = map.x0 + (i + 0.5) * dx - X, b = map.y0 + (j + 0.5) * dy - Y;
  return column_kernel<K>(std::sqrt(a * a + b * b) * inv_h);
}

// Adds particle (X, Y, mass, h) to the map.
template <class K>
void splat(ColumnDensityMap& map, Real X, Real Y, Real mass, Real h, std::vector<Real>& weights) {
  const Real dx = (map.x1 - map.x0) / map.nx, dy = (map.y1 - map.y0) / map.ny;
  h = std::max(h, 0.5 * std::max(dx, dy));
  const Real r = K::support * h, inv_h = 1 / h;
  int i0 = static_cast<int>(std::floor((X - r - map.x0) / dx)), i1 = static_cast<int>(std::ceil((X + r - map.x0) / dx));
  int j0 = static_cast<int>(std::floor((Y - r - map.y0) / dy)), j1 = static_cast<int>(std::ceil((Y + r - map.y0) / dy));
  if (i1 < 0 || j1 < 0 || i0 >= map.nx || j0 >= map.ny) return;
  if (r > kWidePixels * dx && r > kWidePixels * dy) {
    const Real scale = mass * inv_h * inv_h;
    for (int j = std::max(j0, 0); j <= std::min(j1, map.ny - 1); ++j)
      for (int i = std::max(i0, 0); i <= std::min(i1, map.nx - 1); ++i)
        map.sigma[static_cast<std::size_t>(j) * map.nx + i] += scale * weight_at<K>(map, i, j, X, Y, inv_h, dx, dy);
    return;
  }
  const int wide = i1 - i0 + 1;
  weights.assign(static_cast<std::size_t>(wide) * (j1 - j0 + 1), 0);
  Real sum = 0;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const Real w = weight_at<K>(map, i, j, X, Y, inv_h, dx, dy);
      weights[static_cast<std::size_t>(j - j0) * wide + (i - i0)] = w;
      sum += w;
    }
  if (!(sum > 0)) return;
  const Real scale = mass / (sum * map.pixel_area());
  for (int j = std::max(j0, 0); j <= std::min(j1, map.ny - 1); ++j)
    for (int i = std::max(i0, 0); i <= std::min(i1, map.nx - 1); ++i)
      map.sigma[static_cast<std::size_t>(j) * map.nx + i] += scale * weights[static_cast<std::size_t>(j - j0) * wide + (i - i0)];
}
}  // namespace

template <class K>
ColumnDensityMap column_density(const Real* x, const Real* m, const Real* h, std::size_t n, int axis, Real x0, Real x1,
                                Real y0, Real y1, int nx, int ny, const std::function<bool()>& stop) {
  if (axis < 0 || axis > 2 || !(x1 > x0) || !(y1 > y0) || nx < 1 || ny < 1)
    throw std::invalid_argument("column_density: need axis 0..2, a non-empty extent and pixels");
  ColumnDensityMap map{axis, nx, ny, x0, x1, y0, y1, std::vector<Real>(static_cast<std::size_t>(nx) * ny, 0)};
  const int ia = axis == 0 ? 1 : 0, ib = axis == 2 ? 1 : 2;  // the image axes
  std::vector<Real> weights;
  for (std::size_t b = 0; b < n; ++b) {
    if (b % 64 == 0 && stop && stop()) throw ColumnDensityStopped{};
    splat<K>(map, x[3 * b + ia], x[3 * b + ib], m[b], h[b], weights);
  }
  return map;
}

void write_column_density(const std::string& path, const ColumnDensityMap& map) {
  AtomicFile out(path);
  char line[128];
  std::snprintf(line, sizeof line, "%d,%d,%d,", map.axis, map.nx, map.ny);
  out << line;
  std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.9g\n", map.x0, map.x1, map.y0, map.y1);
  out << line;
  for (int j = 0; j < map.ny; ++j)
    for (int i = 0; i < map.nx; ++i) {
      std::snprintf(line, sizeof line, i + 1 < map.nx ? "%.6e," : "%.6e\n", map.sigma[static_cast<std::size_t>(j) * map.nx + i]);
      out << line;
    }
  out.commit();
}

#define SPHARK_COLUMN_DENSITY(K)                                                                                 \
  template Real column_kernel<K<3>>(Real);                                                                       \
  template ColumnDensityMap column_density<K<3>>(const Real*, const Real*, const Real*, std::size_t, int, Real, \
                                                 Real, Real, Real, int, int, const std::function<bool()>&);
SPHARK_KERNELS(SPHARK_COLUMN_DENSITY)
#undef SPHARK_COLUMN_DENSITY

}  // namespace sphark
