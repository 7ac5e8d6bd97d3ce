// Fig. 5 of seed 004: psi(s) for the mirror, cylinder, sphere and torus (theta = 0, pi) at
// R/a = 2.5, and the theta = pi torus branch near R/a = 2.
#include <cstdio>
#include <stdexcept>

#include "sphark/io/atomic_file.hpp"
#include "ghost_static.hpp"
#include "sphark/boundaries/maps.hpp"

namespace ghost_static {

using namespace sphark;

namespace {
// A valid map value, or an empty CSV cell when the map left its valid range.
std::string cell(const MapResult& m) {
  if (!m.ok()) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.12g", m.psi);
  return buf;
}
}  // namespace

void write_fig5(const Options& opt) {
  sphark::AtomicFile f(opt.out + "/fig5.csv");
  f << "s,mirror,cylinder,sphere,torus_theta0,torus_thetapi\n";
  const int n = 400;
  for (int k = 0; k <= n; ++k) {
    const Real s = -1.0 + static_cast<Real>(k) / n;  // fluid inside; R = 1, torus a = 1, R = 2.5
    f << s << "," << cell(mirror_map(s)) << "," << cell(cylinder_map(s, 1, FluidSide::Inside)) << ","
      << cell(sphere_map(s, 1, FluidSide::Inside)) << "," << cell(torus_map(s, 1, 2.5, 1, FluidSide::Inside)) << ","
      << cell(torus_map(s, 1, 2.5, -1, FluidSide::Inside)) << "\n";
  }
  f.commit();
  sphark::AtomicFile b(opt.out + "/fig5_branch.csv");
  b << "s,ra_2.01,ra_2.00,ra_1.99,ra_1.90\n";
  for (int k = 0; k <= n; ++k) {
    const Real s = -1.0 + static_cast<Real>(k) / n;
    b << s;
    for (Real ra : {2.01, 2.00, 1.99, 1.90}) b << "," << cell(torus_map(s, 1, ra, -1, FluidSide::Inside));
    b << "\n";
  }
  b.commit();
  std::printf("fig5: %s/fig5.csv, fig5_branch.csv (empty cells: ghost would cross the torus axis)\n",
              opt.out.c_str());
}

}  // namespace ghost_static
