// Figs. 6-8 of seed 004: node density (eq. 3) of relaxed inner particles and of their ghosts by
// the mirror Psi0 and by the density-preserving map Psi, versus s, for a periodic cylinder
// (R = 1, z in [-3, 3]), a sphere (R = 1) and a torus (a = 1, R = 3).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <vector>

#include "sphark/core/profile.hpp"
#include "sphark/io/atomic_file.hpp"
#include "ghost_static.hpp"
#include "sphark/boundaries/static_profile.hpp"
#include "sphark/io/vtk_series.hpp"

namespace ghost_static {

using namespace sphark;

namespace {

struct Geometry {
  const char* name;
  Wall<3> wall;
  PeriodicBox<3> relax_box;              // fully periodic, holds the geometry
  std::optional<PeriodicBox<3>> eval_box;  // physical periodic axes (cylinder: z)
  Real volume;
  Real s_min;  // deepest inner s (-R or -a)
};

PeriodicBox<3> box(Vec<3> lo, Vec<3> hi, bool px = true, bool py = true, bool pz = true) {
  PeriodicBox<3> b;
  b.lo = lo;
  b.hi = hi;
  b.periodic = {px, py, pz};
  return b;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void write_particles(const std::string& path, const std::vector<Real>& x, const NodeDensityProfile<3>& p, Real n0) {
  sphark::AtomicFile f(path);
  f << "x,y,z,s,n,ghost\n";
  for (std::size_t i = 0; i < p.s_inner.size(); ++i)
    f << x[3 * i] << "," << x[3 * i + 1] << "," << x[3 * i + 2] << "," << p.s_inner[i] << "," << p.n_inner[i] / n0 << ",0\n";
  for (std::size_t g = 0; g < p.s_ghost.size(); ++g)
    f << p.x_ghost[3 * g] << "," << p.x_ghost[3 * g + 1] << "," << p.x_ghost[3 * g + 2] << "," << p.s_ghost[g] << ","
      << p.n_ghost[g] / n0 << ",1\n";
  f.commit();
}

// The same particles as a .vtp (ParaView): arrays node_density (n / n0), s, ghost (0/1).
void write_particles_vtp(const std::string& path, const std::vector<Real>& x, const NodeDensityProfile<3>& p, Real n0) {
  std::vector<Real> pos(x);
  pos.insert(pos.end(), p.x_ghost.begin(), p.x_ghost.end());
  std::vector<Real> n, s, ghost;
  for (Real v : p.n_inner) n.push_back(v / n0);
  for (Real v : p.n_ghost) n.push_back(v / n0);
  s = p.s_inner;
  s.insert(s.end(), p.s_ghost.begin(), p.s_ghost.end());
  ghost.assign(p.s_inner.size(), 0.0);
  ghost.resize(s.size(), 1.0);
  ParticleFrame frame;
  frame.dim = 3;
  frame.count = s.size();
  frame.positions = pos.data();
  frame.arrays = {{"node_density", n.data(), 1}, {"s", s.data(), 1}, {"ghost", ghost.data(), 1}};
  ScopedPhase phase(Phase::Output);
  write_vtp(path, frame, 0);
}

}  // namespace

void run_static(const Options& opt) {
  const std::vector<Geometry> geometries = {
      {"cylinder", Cylinder<3>{Vec<3>::Zero(), 1, FluidSide::Inside}, box(Vec<3>(-1, -1, -3), Vec<3>(1, 1, 3)),
       box(Vec<3>(-3, -3, -3), Vec<3>(3, 3, 3), false, false, true), 6 * kPi, -1},
      {"sphere", Sphere{Vec<3>::Zero(), 1, FluidSide::Inside}, box(Vec<3>(-1, -1, -1), Vec<3>(1, 1, 1)), std::nullopt,
       4 * kPi / 3, -1},
      {"torus", Torus{Vec<3>::Zero(), 3, 1, FluidSide::Inside}, box(Vec<3>(-4, -4, -1), Vec<3>(4, 4, 1)), std::nullopt,
       2 * kPi * kPi * 3, -1},
  };
  sphark::AtomicFile summary(opt.out + "/static_summary.csv");
  summary << "relax_map,geometry,inner,h,H,bulk_rel_std,wall_rel_std,ghosts_psi,ghosts_mirror,invalid_psi,"
             "ghost_dev_psi_pct,ghost_dev_mirror_pct,inner_dev_psi_pct,inner_dev_mirror_pct,relax_s,eval_s\n";

  // With mirror ghosts in the loop the near-wall relaxation cannot reach a flat n (the mirror's
  // ghost deficit is not a local rearrangement): it is stopped after 150 iterations.
  RelaxOptions relax_options;
  if (opt.relax_with_mirror) relax_options.max_iterations = 150;
  for (const Geometry& geo : geometries) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::size_t n_box =
        static_cast<std::size_t>(std::lround(static_cast<Real>(opt.particles) * geo.relax_box.length().prod() / geo.volume));
    const RelaxedSet<3> set = relaxed_set<3>(geo.wall, geo.relax_box, n_box,
                                             opt.relax_with_mirror ? GhostMap::Mirror : GhostMap::DensityPreserving, geo.eval_box,
                                             [](const Vec<3>&) { return true; }, 3, opt.seed, relax_options);
    const double t_relax = seconds_since(t0);
    const Real h = set.bulk.h, H = 2 * h;

    const auto t1 = std::chrono::steady_clock::now();
    const NodeDensityProfile<3> pm = node_density_profile<3>(geo.wall, set.x, h, GhostMap::DensityPreserving, kInfinity, geo.eval_box);
    const NodeDensityProfile<3> p0 = node_density_profile<3>(geo.wall, set.x, h, GhostMap::Mirror, kInfinity, geo.eval_box);
    const double t_eval = seconds_since(t1);

    // interior: inner particles farther than H from the wall (they see no ghost)
    const Real n0 = mean_in_range(pm.s_inner, pm.n_inner, -kInfinity, -H).mean;
    const auto dev = [&](const std::vector<Real>& s, const std::vector<Real>& n, Real lo, Real hi) {
      return 100 * (mean_in_range(s, n, lo, hi).mean / n0 - 1);
    };
    const Real gm = dev(pm.s_ghost, pm.n_ghost, 0, H), g0 = dev(p0.s_ghost, p0.n_ghost, 0, H);
    const Real im = dev(pm.s_inner, pm.n_inner, -H, 0), i0 = dev(p0.s_inner, p0.n_inner, -H, 0);
    summary << (opt.relax_with_mirror ? "mirror" : "psi") << "," << geo.name << "," << set.x.size() / 3 << "," << h << "," << H << "," << set.bulk.rel_std << ","
            << set.wall.rel_std << "," << pm.s_ghost.size() << "," << p0.s_ghost.size() << "," << pm.invalid << "," << gm
            << "," << g0 << "," << im << "," << i0 << "," << t_relax << "," << t_eval << "\n";
    summary.commit();  // the rows so far, atomically
    std::printf("static %-8s %zu inner, H = %.4f (relax %.1f s: bulk std %.2f%%, wall std %.2f%%; eval %.1f s)\n"
                "         ghosts in (0, H]: Psi %+.2f%%  Psi0 %+.2f%%;  inner in (-H, 0]: Psi %+.2f%%  Psi0 %+.2f%%\n",
                geo.name, set.x.size() / 3, H, t_relax, 100 * set.bulk.rel_std, 100 * set.wall.rel_std, t_eval, gm, g0,
                im, i0);
    std::fflush(stdout);

    // profile: bin means of n / n0 in bins H/4 wide with an edge at s = 0; s < 0 inner, s > 0 ghosts
    const Real width = H / 4;
    Real s_max = 0;
    for (Real s : p0.s_ghost) s_max = std::max(s_max, s);
    for (Real s : pm.s_ghost) s_max = std::max(s_max, s);
    sphark::AtomicFile prof(opt.out + "/profile_" + geo.name + ".csv");
    prof << "s,n_mirror,n_map\n";
    const auto bin = [&](const std::vector<Real>& s, const std::vector<Real>& n, Real lo, Real hi) -> std::string {
      const BinMean b = mean_in_range(s, n, lo, hi);
      return b.count ? std::to_string(b.mean / n0) : std::string();
    };
    const int k_in = static_cast<int>(std::ceil(-geo.s_min / width));
    for (int k = k_in; k >= 1; --k) {  // inner: (-k w, -(k-1) w]
      const Real lo = -k * width, hi = -(k - 1) * width;
      prof << lo + 0.5 * width << "," << bin(p0.s_inner, p0.n_inner, lo, hi) << "," << bin(pm.s_inner, pm.n_inner, lo, hi)
           << "\n";
    }
    for (int k = 1; (k - 1) * width < s_max; ++k) {  // ghosts: ((k-1) w, k w]
      const Real lo = (k - 1) * width, hi = k * width;
      prof << lo + 0.5 * width << "," << bin(p0.s_ghost, p0.n_ghost, lo, hi) << "," << bin(pm.s_ghost, pm.n_ghost, lo, hi)
           << "\n";
    }
    prof.commit();
    write_particles(opt.out + "/particles_" + geo.name + "_map.csv", set.x, pm, n0);
    write_particles(opt.out + "/particles_" + geo.name + "_mirror.csv", set.x, p0, n0);
    write_particles_vtp(opt.out + "/particles_" + geo.name + "_map.vtp", set.x, pm, n0);
    write_particles_vtp(opt.out + "/particles_" + geo.name + "_mirror.vtp", set.x, p0, n0);
  }
  std::printf("static: %s/static_summary.csv, profile_<geometry>.csv, particles_<geometry>_{map,mirror}.{csv,vtp}\n",
              opt.out.c_str());
}

}  // namespace ghost_static
