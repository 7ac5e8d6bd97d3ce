#include "cases.hpp"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "sphark/io/csv_writer.hpp"
#include "sphark/io/progress.hpp"
#include "sphark/io/visualise.hpp"
#include "sphark/io/vtk_series.hpp"

namespace cylinder_lattice {

using namespace sphark;

GhostMap parse_map(const std::string& name) { return name == "mirror" ? GhostMap::Mirror : GhostMap::DensityPreserving; }

namespace {
std::mutex print_mutex;

// Particle fields of state y as CSV text (for the Fig. 9 interpolation in vis/cylinder_lattice.py).
std::string fields_csv(const LatticeSystem& sys, const Real* y) {
  std::ostringstream os;
  os.precision(10);
  os << "x,y,vx,vy,rho,h\n";
  const Real* x = y + sys.position_offset();
  const Real* v = y + sys.velocity_offset();
  for (std::size_t a = 0; a < sys.particles(); ++a)
    os << x[2 * a] << ',' << x[2 * a + 1] << ',' << v[2 * a] << ',' << v[2 * a + 1] << ',' << sys.density()[a] << ','
       << sys.smoothing_length()[a] << '\n';
  return os.str();
}

struct RunOutcome {
  std::string map;
  LatticeRunResult result;
  double wall_seconds = 0;
};

// One run with a VTK series (real particles and ghosts), per-frame CSVs and progress lines.
RunOutcome run_with_outputs(const Settings& s, const std::string& map, const std::filesystem::path& dir,
                            const std::string& label, bool single_thread) {
#ifdef _OPENMP
  if (single_thread) omp_set_num_threads(1);
#endif
  std::filesystem::create_directories(dir);
  LatticeRunConfig cfg = s.run;
  cfg.params.map = parse_map(map);
  VtkSeriesWriter fluid(dir, "lattice"), ghosts(dir, "ghosts");
  std::ostringstream progress_text;
  ProgressReporter progress(0, cfg.t_end, 20, progress_text);
  int frame = 0;
  const auto observe = [&](Real t, LatticeSystem& sys, const Real* y) {
    ParticleFrame f;
    f.dim = 2;
    f.count = sys.particles();
    f.positions = y + sys.position_offset();
    f.arrays = {{"velocity", y + sys.velocity_offset(), 2},
                {"density", sys.density().data(), 1},
                {"h", sys.smoothing_length().data(), 1},
                {"pressure", sys.pressure().data(), 1}};
    fluid.write(f, t);
    ParticleFrame g;
    g.dim = 2;
    g.count = sys.ghost_count();
    g.positions = sys.all_positions().data() + 2 * sys.particles();
    g.arrays = {{"velocity", sys.ghosts().velocities(), 2},
                {"density", sys.density().data() + sys.particles(), 1},
                {"h", sys.smoothing_length().data() + sys.particles(), 1}};
    if (g.count > 0) ghosts.write(g, t);
    char name[64];
    std::snprintf(name, sizeof name, "fields_%04d.csv", frame++);
    write_file_atomically(dir / name, "# t=" + std::to_string(t) + "\n" + fields_csv(sys, y));
    if (progress.update(t, sys.rhs_calls(), 0)) {
      std::lock_guard<std::mutex> lock(print_mutex);
      std::fprintf(stderr, "%s: %s", label.c_str(), progress_text.str().c_str());
      progress_text.str("");
    }
  };
  const auto w0 = std::chrono::steady_clock::now();
  RunOutcome out{map, run_lattice(cfg, s.core.output_every, observe), 0};
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
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

int run_single(const Settings& s) {
  const std::string map = s.maps.front();
  const RunOutcome o = run_with_outputs(s, map, s.core.out / ("single_" + map), "single " + map, false);
  print_outcome("single " + map, o);
  write_file_atomically(s.core.out / ("single_" + map) / "summary.csv", summary_csv({o}));
  return o.result.reason == "t_end" ? 0 : 3;
}

int run_medium(const Settings& s) {
  std::vector<RunOutcome> runs(s.maps.size());
  const bool parallel = s.maps.size() > 1 && s.core.threads != 1;
  if (parallel) {  // one map per thread, each run single-threaded
    std::vector<std::thread> pool;
    for (std::size_t k = 0; k < s.maps.size(); ++k)
      pool.emplace_back([&, k] { runs[k] = run_with_outputs(s, s.maps[k], s.core.out / s.maps[k], "medium " + s.maps[k], true); });
    for (auto& t : pool) t.join();
  } else {
    for (std::size_t k = 0; k < s.maps.size(); ++k)
      runs[k] = run_with_outputs(s, s.maps[k], s.core.out / s.maps[k], "medium " + s.maps[k], false);
  }
  int status = 0;
  for (const auto& o : runs) {
    print_outcome("medium " + o.map, o);
    if (o.result.reason != "t_end") status = 3;
  }
  write_file_atomically(s.core.out / "summary.csv", summary_csv(runs));
  if (s.core.render) {
    std::vector<std::string> args{"fig9", s.core.out.string()};
    for (const auto& m : s.maps) args.push_back(m);
    if (!run_python("cylinder_lattice.py", args, false)) return 1;
  }
  return status;
}

int run_ensemble_case(const Settings& s) {
  std::vector<EnsembleJob> jobs;
  for (const auto& m : s.maps)
    for (Real v0 : s.v0s)
      for (int seed = 1; seed <= s.seeds; ++seed) jobs.push_back({parse_map(m), v0, static_cast<unsigned>(seed)});
  const int threads = s.core.threads > 0 ? s.core.threads : 2;
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
  for (std::size_t i = 0; i < jobs.size(); ++i) {
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
