#include "drop_run.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "sphark/io/csv_writer.hpp"
#include "sphark/io/visualise.hpp"

namespace sphark {
namespace {

const DropRunSummary* find_run(const DropResults& results, const std::string& name) {
  for (const auto& [label, r] : results)
    if (label == name) return &r;
  return nullptr;
}

// The cleaning comparison of one scheme (runs <prefix>cleaned and <prefix>control): seed 000,
// Figs. 8-10 -- mean |div v|, maximum density error, kinetic energy.
void print_cleaning_ratios(const DropResults& results, const std::string& prefix, const std::string& scheme) {
  const DropRunSummary* c = find_run(results, prefix + "cleaned");
  const DropRunSummary* u = find_run(results, prefix + "control");
  if (!c || !u) return;
  std::printf("%s, cleaned vs control: time-averaged mean |div v| %.2fx lower, max density error %.2fx lower,"
              " kinetic energy at the end %+.3g%%\n",
              scheme.c_str(), u->mean_abs_div_v_time_avg / c->mean_abs_div_v_time_avg,
              u->max_rel_density_error / c->max_rel_density_error,
              100 * (c->kinetic_energy_end - u->kinetic_energy_end) / u->kinetic_energy_end);
}

}  // namespace

void write_drop_summary(const std::filesystem::path& out, const DropResults& results) {
  std::ostringstream s;
  s << "run,ok,t_reached,particles,wall_s,steps,attempts,rhs_evals,error_test_failures,max_semi_axis_error,"
       "squeeze_error,mean_abs_div_v_time_avg,max_rel_density_error,kinetic_energy_end,total_energy_drift\n";
  for (const auto& [label, r] : results) {
    char line[512];
    std::snprintf(line, sizeof line, "%s,%d,%.9g,%zu,%.4g,%ld,%ld,%ld,%ld,%.6g,%.6g,%.6g,%.6g,%.9g,%.6g\n", label.c_str(),
                  r.loop.ok() ? 1 : 0, r.loop.t_reached, r.particles, r.loop.wall_seconds, r.loop.stats.steps,
                  r.loop.stats.attempts, r.loop.stats.rhs_evals, r.loop.stats.error_test_failures, r.max_semi_axis_error, r.squeeze_error,
                  r.mean_abs_div_v_time_avg, r.max_rel_density_error, r.kinetic_energy_end, r.total_energy_drift);
    s << line;
  }
  write_file_atomically(out / "summary.csv", s.str());
  print_cleaning_ratios(results, "seed_", "seed's plain WCSPH (delta = 0)");
  print_cleaning_ratios(results, "", "delta-SPH");
}

// One run's pictures: its semi-axes against the exact ellipse and its frames at t = 0, the first
// squeeze (t ~ 0.012), the first maximum along x (t ~ 0.035) and the end.
std::vector<PythonJob> drop_run_pictures(const std::filesystem::path& out, const std::string& label, Real frame_every,
                                         Real t_end) {
  std::vector<PythonJob> jobs;
  jobs.push_back({"charts.py",
                  {"--csv", (out / label / "diagnostics.csv").string(), "--x", "t", "--y", "semi_axis_x", "--y-extra",
                   "semi_axis_x_exact:a exact", "--y-extra", "semi_axis_y", "--y-extra", "semi_axis_y_exact:b exact",
                   "--ylabel", "semi-axis", "--title", "water drop, " + run_legend(label) + ": semi-axes vs exact ellipse",
                   "--out", (out / ("semi_axes_" + label + ".png")).string()}});
  PythonJob frames{"render_particles.py", {(out / label / "drop.pvd").string(), "--grid", "2x2", "--frames"}};
  for (Real t : {0.0, 0.012, 0.035}) frames.args.push_back(std::to_string(std::lround(std::min(t, t_end) / frame_every)));
  frames.args.insert(frames.args.end(), {"-1", "--array", "pressure", "--title", "water drop, " + run_legend(label),
                                         "--out", (out / ("frames_" + label + ".png")).string()});
  jobs.push_back(std::move(frames));
  return jobs;
}

// The pictures left in one Python process (vis/batch.py): the charts of Figs. 8-10 with every run
// (the seed's scheme solid, delta-SPH dashed by its label), and the pictures of the runs in
// `pending` (drop_run_pictures; the others were drawn while runs still went on).
void make_drop_pictures(const std::filesystem::path& out, const DropResults& results, const std::vector<std::string>& pending,
                        Real frame_every, Real t_end) {
  std::vector<PythonJob> jobs;
  const auto chart = [&](const std::string& y, const std::string& ylabel, const std::string& png, bool logy,
                         const std::string& title) {
    PythonJob job{"charts.py", {}};
    for (const auto& [label, r] : results)
      job.args.insert(job.args.end(), {"--csv", (out / label / "diagnostics.csv").string() + ":" + run_legend(label)});
    std::string styles;  // the seed's runs solid, delta-SPH's dashed
    for (const auto& [label, r] : results) {
      if (!styles.empty()) styles += ',';
      styles += label.rfind("seed_", 0) == 0 ? "-" : "--";
    }
    job.args.insert(job.args.end(), {"--styles=" + styles, "--x", "t", "--y", y, "--ylabel", ylabel, "--title", title, "--out", (out / png).string()});
    if (logy) job.args.push_back("--logy");
    jobs.push_back(std::move(job));
  };
  chart("mean_abs_div_v", "mean |div v|  [1/s]", "div_v.png", true, "water drop: mean velocity divergence (paper Fig. 8)");
  chart("max_rel_density_error", "max |rho - rho0| / rho0", "density_error.png", false,
        "water drop: maximum density error (paper Fig. 9)");
  chart("kinetic_energy", "kinetic energy  [J/m]", "kinetic_energy.png", false, "water drop: kinetic energy (paper Fig. 10)");
  for (const std::string& label : pending)
    for (PythonJob& job : drop_run_pictures(out, label, frame_every, t_end)) jobs.push_back(std::move(job));
  run_python_batch(jobs, true);
}

std::string run_legend(const std::string& run) {
  const bool seed = run.rfind("seed_", 0) == 0;
  const std::string cleaning = run.substr(seed ? 5 : 0);
  return (seed ? "seed's WCSPH, " : "delta-SPH, ") + cleaning;
}

}  // namespace sphark
