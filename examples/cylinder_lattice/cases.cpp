#include "cases.hpp"

#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "sphark/io/csv_writer.hpp"
#include "sphark/io/paraview_state.hpp"
#include "sphark/io/progress.hpp"
#include "sphark/io/visualise.hpp"
#include "sphark/run/run_outputs.hpp"
#include "sphark/run/signals.hpp"
#include "sphark/run/time_loop.hpp"

namespace cylinder_lattice {

using namespace sphark;

GhostMap parse_map(const std::string& name) { return name == "mirror" ? GhostMap::Mirror : GhostMap::DensityPreserving; }

namespace {
std::mutex print_mutex;

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Particle fields of state y as CSV text (for the Fig. 9 interpolation in vis/cylinder_lattice.py);
// x = the positions wrapped into the box.
std::string fields_csv(const LatticeSystem& sys, const Real* y, const std::vector<Real>& x) {
  std::ostringstream os;
  os.precision(10);
  os << "x,y,vx,vy,rho,h\n";
  const Real* v = y + sys.velocity_offset();
  for (std::size_t a = 0; a < sys.particles(); ++a)
    os << x[2 * a] << ',' << x[2 * a + 1] << ',' << v[2 * a] << ',' << v[2 * a + 1] << ',' << sys.density()[a] << ','
       << sys.smoothing_length()[a] << '\n';
  return os.str();
}

// The ghost series up to a checkpoint: its particle frame list ("t lattice_NNNNN.vtp" lines)
// with the ghosts' file of each frame, where that file exists in `dir`.
std::string ghost_frames(const std::string& lattice_frames, const std::filesystem::path& dir) {
  std::istringstream in(lattice_frames);
  std::string text;
  for (std::string line; std::getline(in, line);) {
    const auto at = line.find("lattice_");
    if (at == std::string::npos) continue;
    line.replace(at, 8, "ghosts_");
    if (std::filesystem::exists(dir / line.substr(line.find(' ') + 1))) text += line + "\n";
  }
  return text;
}

struct RunOutcome {
  std::string map;
  LatticeRunResult result;
  TimeLoopResult loop;
  double wall_seconds = 0;
};

// One run through the shared driver (run/time_loop.hpp): a VTK series of the real particles,
// per frame the ghosts and a fields CSV, checkpoints, --restart, signals, last good state. The
// penetration / accumulation roots (seed 004, eq. 37) end the run at their root time.
RunOutcome run_with_outputs(const Settings& s, const std::string& map, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  LatticeRunConfig cfg = s.run;
  cfg.params.map = parse_map(map);
  RunOutcome out{map, {}, {}, 0};
  const double cpu0 = process_cpu_seconds();
  const LatticeParams p = lattice_params(cfg.params, cfg.particles);
  LatticeSystem sys(cfg.particles, p);
  std::vector<Real> y(sys.size(), 0.0);  // at rest
  if (!s.restart) {
    const std::vector<Real> x0 = initial_positions(cfg);
    std::copy(x0.begin(), x0.end(), y.begin() + static_cast<std::ptrdiff_t>(sys.position_offset()));
  }
  TimeLoopSettings ts;
  ts.program = "cylinder_lattice";
  ts.run = map;
  ts.argv = s.argv;
  ts.texts = {{"scene", scene_text(s, map)}};
  ts.t_end = cfg.t_end;
  ts.sample_every = s.core.output_every > 0 ? s.core.output_every : cfg.t_end;
  ts.diagnostics_csv = dir / "diagnostics.csv";
  ts.columns = {"t", "kinetic_energy", "min_ghost_h_over_h_ref", "wall_force_x", "wall_force_y", "steps", "rhs_evals"};
  ts.frames_dir = dir;
  ts.frames_basename = "lattice";
  ts.frame_every = ts.sample_every;
  apply_run_control(ts, s.control, s.restart, dir / "checkpoint.bin");
  ts.progress_interval = 10;

  ResumableVtkSeries ghosts(dir, "ghosts");  // frame k of the ghosts goes with lattice_k
  if (s.restart) ghosts.restore(ghost_frames(s.restart->text("frames"), dir));
  Real sampled_g[2] = {1, 1};
  std::vector<Real> wrapped(2 * cfg.particles);  // output positions, wrapped into the box
  TimeLoopHooks hooks;
  hooks.diagnostics = [&](Real t, const Real* yy, const StepperStats& st) {
    const int rc = sys.prepare(yy);  // density, h, ghosts of this state
    if (rc != 0 || sys.roots(t, yy, sampled_g) != 0) sampled_g[0] = sampled_g[1] = 1;
    Real ke = 0;
    const Real* v = yy + sys.velocity_offset();
    for (std::size_t i = 0; i < 2 * sys.particles(); ++i) ke += 0.5 * p.mass * v[i] * v[i];
    const Vec<2> f = rc == 0 ? sys.wall_force() : Vec<2>(NAN, NAN);
    return std::vector<Real>{t, ke, rc == 0 ? sys.min_ghost_h() / p.h_ref : NAN, f[0], f[1],
                             static_cast<Real>(st.steps), static_cast<Real>(st.rhs_evals)};
  };
  hooks.frame = [&](Real t, const Real* yy) {  // after diagnostics(): prepared at this state
    ParticleFrame g;
    g.dim = 2;
    g.count = sys.ghost_count();
    g.positions = sys.all_positions().data() + 2 * sys.particles();
    g.arrays = {{"velocity", sys.ghosts().velocities(), 2},
                {"density", sys.density().data() + sys.particles(), 1},
                {"h", sys.smoothing_length().data() + sys.particles(), 1}};
    if (g.count > 0) ghosts.write(g, t);
    char name[64];  // fields_NNNN.csv on the frame grid, fields_end.csv at an event or a failure
    const Real k = std::round(t / ts.frame_every);
    if (std::abs(t - k * ts.frame_every) <= 1e-9 * ts.frame_every)
      std::snprintf(name, sizeof name, "fields_%04ld.csv", static_cast<long>(k));
    else
      std::snprintf(name, sizeof name, "fields_end.csv");
    lattice_box(p).wrap_all(yy + sys.position_offset(), sys.particles(), wrapped.data());
    write_file_atomically(dir / name, "# t=" + std::to_string(t) + "\n" + fields_csv(sys, yy, wrapped));
    ParticleFrame f;
    f.dim = 2;
    f.count = sys.particles();
    f.positions = wrapped.data();
    f.arrays = {{"velocity", yy + sys.velocity_offset(), 2},
                {"density", sys.density().data(), 1},
                {"h", sys.smoothing_length().data(), 1},
                {"pressure", sys.pressure().data(), 1}};
    return f;
  };
  const auto event = [&](const Real* g) {
    if (g[0] <= 0) out.result.reason = "penetration";
    else if (g[1] <= 0) out.result.reason = "accumulation";
    return !out.result.reason.empty();
  };
  // Events already present at a sample (at t = 0: no sign change for the stepper to see); the
  // event functions of the sampled state come from diagnostics(), called just before.
  hooks.finished = [&](Real) { return event(sampled_g); };
  hooks.root = [&](Real, const std::vector<int>& found) {
    Real g[2] = {1, 1};
    if (!found.empty() && found[0] != 0) g[0] = 0; else g[1] = 0;
    return event(g);
  };
  const auto w0 = std::chrono::steady_clock::now();
  out.loop = run_time_loop(sys, sys.layout(), cfg.stepper, y, ts, hooks);
  write_paraview_state_or_warn(dir / "view.pvsm", {{"lattice.pvd", "velocity"}});
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  out.result.t_max = out.loop.t_reached;
  out.result.stats = out.loop.stats;
  out.result.rhs_calls = out.loop.stats.rhs_evals;
  if (out.loop.status == TimeLoopStatus::Reached) out.result.reason = "t_end";
  if (out.loop.status == TimeLoopStatus::Failed) out.result.reason = "failure: " + out.loop.failure;
  if (out.loop.status == TimeLoopStatus::Stopped) out.result.reason = "stopped";
  out.result.cpu_seconds = process_cpu_seconds() - cpu0;
  return out;
}

void print_outcome(const std::string& label, const RunOutcome& o) {
  std::printf("%-22s t_max %.4g  reason %s  rhs %ld  steps %ld  cpu %.1f s  wall %.1f s\n", label.c_str(),
              o.result.t_max, o.result.reason.c_str(), o.result.rhs_calls, o.result.stats.steps, o.result.cpu_seconds,
              o.wall_seconds);
}

std::string summary_csv(const std::vector<RunOutcome>& runs) {
  std::ostringstream os;
  os << "map,t_max,reason,steps,rhs_calls,cpu_seconds,wall_seconds\n";
  for (const auto& r : runs)
    os << r.map << ',' << r.result.t_max << ",\"" << r.result.reason << "\"," << r.result.stats.steps << ','
       << r.result.rhs_calls << ',' << r.result.cpu_seconds << ',' << r.wall_seconds << '\n';
  return os.str();
}
}  // namespace

std::string scene_text(const Settings& s, const std::string& map) {
  const LatticeParams& p = s.run.params;
  std::string text;
  append_key_value(text, "case", s.kase);
  append_key_value(text, "map", map);
  append_key_value(text, "bc", s.bc);
  append_key_value(text, "particles", static_cast<Real>(s.run.particles));
  append_key_value(text, "seed", static_cast<Real>(s.run.seed));
  append_key_value(text, "min_separation", s.run.min_separation);
  append_key_value(text, "relax_iterations", static_cast<Real>(s.run.relax_iterations));
  append_key_value(text, "v0", p.v0);
  append_key_value(text, "tau", p.tau);
  append_key_value(text, "sound_speed", p.sound_speed);
  append_key_value(text, "background_pressure", p.background);
  append_key_value(text, "rho0", p.rho0);
  append_key_value(text, "eta", p.eta);
  append_key_value(text, "alpha", p.alpha);
  append_key_value(text, "cfl", p.cfl);
  append_key_value(text, "accumulation", p.accumulation);
  append_key_value(text, "stepper", s.core.stepper);
  return text;
}

int run_single(const Settings& s) {
  const std::string map = s.maps.front();
  const RunOutcome o = run_with_outputs(s, map, s.core.out / ("single_" + map));
  print_outcome("single " + map, o);
  write_file_atomically(s.core.out / ("single_" + map) / "summary.csv", summary_csv({o}));
  return report_time_loop_end(o.loop);
}

// The maps one after the other (each may use every OpenMP thread); a stop signal or a failure
// ends the case after that map's run (its checkpoint names the map: --restart resumes it).
int run_medium(const Settings& s) {
  std::vector<RunOutcome> runs;
  int status = 0;
  for (const auto& map : s.maps) {
    runs.push_back(run_with_outputs(s, map, s.core.out / map));
    print_outcome("medium " + map, runs.back());
    status = report_time_loop_end(runs.back().loop);
    if (status != 0) break;
  }
  write_file_atomically(s.core.out / (s.maps.size() > 1 ? "summary.csv" : "summary_" + s.maps[0] + ".csv"),
                        summary_csv(runs));
  if (status != 0) return status;
  if (s.core.render) {
    std::vector<std::string> args{"fig9", s.core.out.string()};
    for (const auto& m : s.maps) args.push_back(m);
    if (!run_python("cylinder_lattice.py", args, false)) return 1;
    for (const auto& m : s.maps)  // the VTK series' last frame: speed, v_y and pressure
      run_python("render_particles.py",
                 {(s.core.out / m / "lattice.pvd").string(), "--grid", "1x2", "--frame", "-1", "--arrays", "velocity",
                  "pressure", "--out", (s.core.out / m / "final.png").string()},
                 true);
  }
  return 0;
}

int run_ensemble_case(const Settings& s) {
  std::vector<EnsembleJob> jobs;
  for (const auto& m : s.maps)
    for (Real v0 : s.v0s)
      for (int seed = 1; seed <= s.seeds; ++seed) jobs.push_back({parse_map(m), v0, static_cast<unsigned>(seed)});
  const int threads = s.core.threads > 0 ? s.core.threads : 2;
  install_stop_handlers();  // SIGINT/SIGTERM: the runs in progress finish, the CSVs hold the runs done
  std::fprintf(stderr, "cylinder_lattice: ensemble of %zu runs on %d thread(s)\n", jobs.size(), threads);
  const auto w0 = std::chrono::steady_clock::now();
  std::size_t done = 0;
  const auto results = run_ensemble(s.run, jobs, threads, [&](std::size_t i, const LatticeRunResult& r) {
    ++done;
    if (done % 20 == 0 || done == jobs.size())
      std::fprintf(stderr, "  %zu/%zu runs (last: %s v0=%.2f seed %u: t_max %.3g %s)\n", done, jobs.size(),
                   map_name(jobs[i].map).c_str(), jobs[i].v0, jobs[i].seed, r.t_max, r.reason.c_str());
  });
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  std::ostringstream csv, runs;
  csv << "map,v0,seed,t_max,reason\n";
  runs << "map,v0,seed,t_max,reason,steps,rhs_calls,cpu_seconds\n";
  double cpu = 0;
  std::size_t completed = 0;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (results[i].reason.empty()) continue;  // not started (stop signal)
    ++completed;
    char row[160];
    std::snprintf(row, sizeof row, "%s,%.2f,%u,%.9g,", map_name(jobs[i].map).c_str(), jobs[i].v0, jobs[i].seed,
                  results[i].t_max);
    std::string reason = results[i].reason;
    for (char& c : reason)
      if (c == '"' || c == '\n' || c == ',') c = ';';
    csv << row << reason << '\n';
    runs << row << reason << ',' << results[i].stats.steps << ',' << results[i].rhs_calls << ','
         << results[i].cpu_seconds << '\n';
    cpu += results[i].cpu_seconds;
  }
  write_file_atomically(s.core.out / "ensemble.csv", csv.str());
  write_file_atomically(s.core.out / "ensemble_runs.csv", runs.str());
  if (const int sig = stop_requested()) {
    std::fprintf(stderr, "cylinder_lattice: ensemble stopped by signal %d after %zu of %zu runs; %s holds them\n", sig,
                 completed, jobs.size(), (s.core.out / "ensemble.csv").c_str());
    return 128 + sig;
  }
  // Table: fraction reaching t_end and mean t_max per map and v0.
  std::printf("%-10s %6s %10s %10s   reasons\n", "map", "v0", "reach_t_end", "mean_t_max");
  for (const auto& m : s.maps)
    for (Real v0 : s.v0s) {
      int reach = 0, count = 0, pen = 0, acc = 0, fail = 0;
      double sum = 0;
      for (std::size_t i = 0; i < jobs.size(); ++i) {
        if (map_name(jobs[i].map) != m || jobs[i].v0 != v0) continue;
        ++count;
        sum += results[i].t_max;
        const std::string& r = results[i].reason;
        if (r == "t_end") ++reach; else if (r == "penetration") ++pen; else if (r == "accumulation") ++acc; else ++fail;
      }
      std::printf("%-10s %6.2f %5d/%-4d %10.3f   penetration %d, accumulation %d, failure %d\n", m.c_str(), v0, reach,
                  count, sum / count, pen, acc, fail);
    }
  std::printf("ensemble: %zu runs, wall %.1f s, total CPU %.1f s, %d thread(s)\n", jobs.size(), wall, cpu, threads);
  if (s.core.render && !run_python("cylinder_lattice.py", {"fig10", s.core.out.string()}, false)) return 1;
  return 0;
}

}  // namespace cylinder_lattice
