// Table 1 of seed 004: CPU time to place the ghosts of N random inner particles with the
// density-preserving map Psi relative to the mirror Psi0 (percentage increase), mean +- std
// over random draws, for a sphere (r = 1), a cylinder (r = 1, L = 2 pi) and a torus (a = 1, R = 3).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "sphark/io/atomic_file.hpp"
#include "ghost_static.hpp"
#include "sphark/boundaries/ghosts.hpp"

namespace ghost_static {

using namespace sphark;

namespace {

struct CostGeometry {
  const char* name;
  Wall<3> wall;
  Vec<3> lo, hi;  // bounding box for rejection sampling
  Real volume;
};

std::vector<Real> random_inside(const CostGeometry& g, std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Real> U(0, 1);
  std::vector<Real> x;
  x.reserve(3 * n);
  std::visit(
      [&](const auto& w) {
        while (x.size() < 3 * n) {
          Vec<3> p;
          for (int k = 0; k < 3; ++k) p[k] = g.lo[k] + (g.hi[k] - g.lo[k]) * U(rng);
          if (w.locate(p).s < 0) x.insert(x.end(), {p[0], p[1], p[2]});
        }
      },
      g.wall);
  return x;
}

// Seconds for one append() of all ghosts (minimum of `reps` runs: the least perturbed by other
// processes on a shared machine).
double time_append(GhostLayer<3>& layer, const Wall<3>& wall, const std::vector<Real>& x,
                   const std::vector<Real>& v, const GhostOptions& o,
                   int reps) {
  double best = 1e300;
  for (int r = 0; r < reps; ++r) {
    layer.clear();
    const auto t0 = std::chrono::steady_clock::now();
    layer.append(wall, x.data(), v.data(), x.size() / 3, o);
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

}  // namespace

void run_cost_table(const Options& opt) {
  const std::vector<CostGeometry> geometries = {
      {"cylinder", Cylinder<3>{Vec<3>::Zero(), 1, FluidSide::Inside}, Vec<3>(-1, -1, 0), Vec<3>(1, 1, 2 * kPi), 2 * kPi * kPi},
      {"sphere", Sphere{Vec<3>::Zero(), 1, FluidSide::Inside}, Vec<3>(-1, -1, -1), Vec<3>(1, 1, 1), 4 * kPi / 3},
      {"torus", Torus{Vec<3>::Zero(), 3, 1, FluidSide::Inside}, Vec<3>(-4, -4, -1), Vec<3>(4, 4, 1), 6 * kPi * kPi},
  };
  sphark::AtomicFile f(opt.out + "/table1.csv");
  f << "geometry,layer,ghosts,mirror_ms,psi_ms,increase_pct_mean,increase_pct_std,draws,particles\n";
  std::printf("table 1: %zu random inner particles, %d draws; increase of ghost-placement time, Psi vs Psi0\n",
              opt.cost_particles, opt.draws);
  GhostLayer<3> layer;
  layer.reserve(opt.cost_particles);
  for (const CostGeometry& g : geometries) {
    const Real dx = std::cbrt(g.volume / static_cast<Real>(opt.cost_particles));
    const Real H = 2 * 1.3 * dx;  // Wendland C4 support at h = 1.3 dx
    for (const Real width : {kInfinity, H}) {
      std::vector<double> pct;
      double tm = 0, tp = 0;
      std::size_t ghosts = 0;
      for (int d = 0; d < opt.draws; ++d) {
        const std::vector<Real> x = random_inside(g, opt.cost_particles, opt.seed * 1000u + static_cast<unsigned>(d));
        std::vector<Real> v(x.size(), 0.25);  // ghosts carry reflected velocities
        GhostOptions om, op;
        om.width = op.width = width;
        om.map = GhostMap::Mirror;
        op.map = GhostMap::DensityPreserving;
        double a = 1e300, b = 1e300;
        for (int round = 0; round < 3; ++round) {  // interleaved, so both see the same machine load
          a = std::min(a, time_append(layer, g.wall, x, v, om, 2));
          b = std::min(b, time_append(layer, g.wall, x, v, op, 2));
        }
        ghosts = layer.size();
        tm += a / opt.draws;
        tp += b / opt.draws;
        pct.push_back(100 * (b / a - 1));
      }
      double mean = 0, var = 0;
      for (double p : pct) mean += p / static_cast<double>(pct.size());
      for (double p : pct) var += (p - mean) * (p - mean) / static_cast<double>(pct.size() - 1);
      const char* layer_name = std::isinf(width) ? "all" : "H";
      f << g.name << "," << layer_name << "," << ghosts << "," << 1e3 * tm << "," << 1e3 * tp << "," << mean << ","
        << std::sqrt(var) << "," << opt.draws << "," << opt.cost_particles << "\n";
      std::printf("  %-8s layer %-3s %8zu ghosts: Psi0 %7.2f ms, Psi %7.2f ms, increase %+6.2f +- %.2f %%\n", g.name,
                  layer_name, ghosts, 1e3 * tm, 1e3 * tp, mean, std::sqrt(var));
      std::fflush(stdout);
      f.commit();  // the rows so far, atomically
    }
  }
}

}  // namespace ghost_static
