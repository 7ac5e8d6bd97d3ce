#include "ensemble_case.hpp"

#include <chrono>
#include <cstdio>
#include <sstream>

#include "sphark/io/csv_writer.hpp"
#include "sphark/io/visualise.hpp"
#include "sphark/run/signals.hpp"

namespace sphark {

namespace {
// The table of the ensemble: fraction reaching t_end and mean t_max per map and v0.
void print_table(const std::vector<EnsembleJob>& jobs, const std::vector<LatticeRunResult>& results,
                 const std::vector<std::string>& maps, const std::vector<Real>& v0s) {
  std::printf("%-10s %6s %10s %10s   reasons\n", "map", "v0", "reach_t_end", "mean_t_max");
  for (const auto& m : maps)
    for (Real v0 : v0s) {
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
}
}  // namespace

int run_lattice_ensemble(const LatticeRunConfig& run, const std::vector<std::string>& maps, const std::vector<Real>& v0s,
                         int seeds, const CoreOptions& core) {
  std::vector<EnsembleJob> jobs;
  for (const auto& m : maps)
    for (Real v0 : v0s)
      for (int seed = 1; seed <= seeds; ++seed)
        jobs.push_back({m == "mirror" ? GhostMap::Mirror : GhostMap::DensityPreserving, v0, static_cast<unsigned>(seed)});
  const int threads = core.threads > 0 ? core.threads : 2;
  install_stop_handlers();  // SIGINT/SIGTERM: the runs in progress stop, the CSVs hold the runs completed
  std::fprintf(stderr, "cylinder_lattice: ensemble of %zu runs on %d thread(s)\n", jobs.size(), threads);
  const auto w0 = std::chrono::steady_clock::now();
  std::size_t done = 0;
  const auto results = run_ensemble(run, jobs, threads, [&](std::size_t i, const LatticeRunResult& r) {
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
    if (results[i].reason.empty() || results[i].reason == "stopped") continue;  // not started / cut short by a stop signal
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
  write_file_atomically(core.out / "ensemble.csv", csv.str());
  write_file_atomically(core.out / "ensemble_runs.csv", runs.str());
  if (const int sig = stop_requested()) {
    std::fprintf(stderr, "cylinder_lattice: ensemble stopped by signal %d after %zu of %zu runs; %s holds them\n", sig,
                 completed, jobs.size(), (core.out / "ensemble.csv").c_str());
    return 128 + sig;
  }
  print_table(jobs, results, maps, v0s);
  std::printf("ensemble: %zu runs, wall %.1f s, total CPU %.1f s, %d thread(s)\n", jobs.size(), wall, cpu, threads);
  if (core.render && !run_python("cylinder_lattice.py", {"fig10", core.out.string()}, false)) return 1;
  return 0;
}

}  // namespace sphark
