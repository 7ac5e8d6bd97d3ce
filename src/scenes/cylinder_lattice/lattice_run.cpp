#include <cmath>
#include <ctime>
#include <exception>
#include <mutex>
#include <random>
#include <stdexcept>

#include "sphark/boundaries/wall_relaxation.hpp"
#include "sphark/run/concurrent_jobs.hpp"
#include "sphark/run/signals.hpp"
#include "sphark/run/time_loop.hpp"  // kStepFloorFraction
#include "sphark/scenes/cylinder_lattice/lattice_run.hpp"

namespace sphark {

namespace {
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
}  // namespace

std::string map_name(GhostMap map) { return map == GhostMap::Mirror ? "mirror" : "nonlinear"; }

StepperOptions lattice_default_stepper() {
  StepperOptions s;
  s.method = "leapfrog";
  s.cfl_safety = 1;  // the CFL number lives in LatticeParams::cfl
  return s;
}

LatticeParams lattice_params(LatticeParams p, std::size_t n) {
  const Real dx = lattice_spacing(p, n);
  p.mass = p.rho0 * dx * dx;  // rho0 * fluid area / n
  p.h_ref = p.eta * dx;       // seed 000 eq. (5) at rho = rho0
  return p;
}

std::vector<Real> random_fluid_positions(const LatticeParams& p, std::size_t n, unsigned seed, Real min_separation) {
  const Real dx = lattice_spacing(p, n), d_min2 = min_separation * dx * min_separation * dx;
  const Real L = 2 * p.half_box, r_min = p.radius + 0.5 * dx;
  const PeriodicBox<2> box = lattice_box(p);
  // Cell grid of side >= d_min for the overlap test.
  const int cells = std::max(1, static_cast<int>(L / (min_separation * dx)));
  const Real cell = L / cells;
  std::vector<std::vector<std::uint32_t>> grid(static_cast<std::size_t>(cells) * cells);
  auto cell_of = [&](Real c) { return std::min(cells - 1, static_cast<int>((c + p.half_box) / cell)); };
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Real> u(-p.half_box, p.half_box);
  std::vector<Real> x;
  x.reserve(2 * n);
  const std::size_t max_attempts = 2000 * n + 100000;
  for (std::size_t attempt = 0; attempt < max_attempts && x.size() < 2 * n; ++attempt) {
    if (attempt % 65536 == 0) throw_if_stop_requested();  // SIGINT/SIGTERM: a long set-up ends here
    const Vec<2> c(u(rng), u(rng));
    if (c.norm() < r_min) continue;
    const int ci = cell_of(c[0]), cj = cell_of(c[1]);
    bool free = true;
    for (int di = -1; di <= 1 && free; ++di)
      for (int dj = -1; dj <= 1 && free; ++dj) {
        const int i = (ci + di + cells) % cells, j = (cj + dj + cells) % cells;
        for (std::uint32_t k : grid[static_cast<std::size_t>(i) * cells + j]) {
          const Vec<2> d = box.minimum_image(c - Vec<2>(x[2 * k], x[2 * k + 1]));
          if (d.squaredNorm() < d_min2) {
            free = false;
            break;
          }
        }
      }
    if (!free) continue;
    grid[static_cast<std::size_t>(ci) * cells + cj].push_back(static_cast<std::uint32_t>(x.size() / 2));
    x.push_back(c[0]);
    x.push_back(c[1]);
  }
  if (x.size() < 2 * n) throw std::runtime_error("random_fluid_positions: could not place the particles");
  return x;
}

std::vector<Real> initial_positions(const LatticeRunConfig& cfg) {
  const LatticeParams p = lattice_params(cfg.params, cfg.particles);
  std::vector<Real> x = random_fluid_positions(p, cfg.particles, cfg.seed, cfg.min_separation);
  if (cfg.relax_iterations <= 0) return x;
  const PeriodicBox<2> box = lattice_box(p);
  RelaxOptions ro;
  ro.h_over_dx = p.eta;
  ro.max_iterations = cfg.relax_iterations;
  ro.tolerance = 5e-3;
  const Wall<2> wall = Cylinder<2>{Vec<2>::Zero(), p.radius, FluidSide::Outside};
  relax_near_wall<2>(x, wall, p.map, p.h_ref, std::vector<char>(cfg.particles, 1), box, ro);
  return x;
}

LatticeRunResult run_lattice(const LatticeRunConfig& cfg, Real output_every, const LatticeObserver& observe) {
  LatticeRunResult res;
  const double cpu0 = thread_cpu_seconds();
  try {
    const LatticeParams p = lattice_params(cfg.params, cfg.particles);
    LatticeSystem sys(cfg.particles, p);
    std::vector<Real> y(sys.size(), 0.0);  // at rest
    const std::vector<Real> x0 = initial_positions(cfg);
    std::copy(x0.begin(), x0.end(), y.begin() + static_cast<std::ptrdiff_t>(sys.position_offset()));
    // Events already present at t = 0 (no sign change for the stepper to see).
    Real g[2];
    if (sys.roots(0, y.data(), g) != 0) {
      res.reason = "failure: " + sys.last_error();
    } else if (g[0] <= 0) {
      res.reason = "penetration";
    } else if (g[1] <= 0) {
      res.reason = "accumulation";
    }
    if (observe) observe(0, sys, y.data());
    if (res.reason.empty()) {
      StepperOptions so = cfg.stepper;  // SIGINT/SIGTERM end the run at its next RHS evaluation
      so.interrupt = [] { return stop_requested() != 0; };
      if (so.step_floor <= 0) so.step_floor = kStepFloorFraction * cfg.t_end;
      auto stepper = make_stepper(sys, so, 0, y.data());
      Real t = 0;
      const Real every = output_every > 0 ? output_every : cfg.t_end;
      for (int k = 1; res.reason.empty(); ++k) {
        const Real t_out = std::min(cfg.t_end, k * every);
        const AdvanceStatus st = stepper->advance(t_out, y.data(), t);
        if (st == AdvanceStatus::Interrupted) {
          res.reason = "stopped";
        } else if (st == AdvanceStatus::Failed) {
          res.reason = "failure: " + stepper->failure_reason();
        } else if (st == AdvanceStatus::RootFound) {
          const std::vector<int> r = stepper->roots_found();
          res.reason = (!r.empty() && r[0] != 0) ? "penetration" : "accumulation";
        } else if (t_out >= cfg.t_end) {
          res.reason = "t_end";
        }
        if (observe && st != AdvanceStatus::Interrupted && (st != AdvanceStatus::Failed || t > 0)) {
          if (sys.prepare(y.data()) == 0) observe(t, sys, y.data());
        }
      }
      res.t_max = t;
      res.stats = stepper->stats();
    }
    res.rhs_calls = sys.rhs_calls();
    res.y = std::move(y);
  } catch (const std::exception& e) {
    res.reason = std::string("failure: ") + e.what();
  } catch (const StopRequested&) {  // during the set-up (random placement, relaxation)
    res.reason = "stopped";
  }
  res.cpu_seconds = thread_cpu_seconds() - cpu0;
  return res;
}

std::vector<LatticeRunResult> run_ensemble(const LatticeRunConfig& cfg, const std::vector<EnsembleJob>& jobs,
                                           int threads,
                                           const std::function<void(std::size_t, const LatticeRunResult&)>& on_done) {
  std::vector<LatticeRunResult> results(jobs.size());
  std::mutex done_mutex;
  // each run single-threaded: the ensemble is spread over threads; SIGINT/SIGTERM: the runs in
  // progress finish, no new ones start
  run_concurrently(jobs.size(), threads, 1, [&](std::size_t i) {
    LatticeRunConfig c = cfg;
    c.params.map = jobs[i].map;
    c.params.v0 = jobs[i].v0;
    c.seed = jobs[i].seed;
    results[i] = run_lattice(c);
    results[i].y.clear();
    if (on_done) {
      std::lock_guard<std::mutex> lock(done_mutex);
      on_done(i, results[i]);
    }
    return true;
  });
  return results;
}

}  // namespace sphark
