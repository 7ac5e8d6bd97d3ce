#include "drop_run.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "sphark/io/csv_writer.hpp"
#include "sphark/io/visualise.hpp"

namespace sphark {

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
  if (results.size() == 2) {
    const DropRunSummary& c = results[0].second;
    const DropRunSummary& u = results[1].second;
    std::printf("cleaned / control: time-averaged mean |div v| %.3g (control/cleaned %.2fx), max density error %.3g"
                " (control/cleaned %.2fx), kinetic energy at end %+.3g%%\n",
                c.mean_abs_div_v_time_avg / u.mean_abs_div_v_time_avg,
                u.mean_abs_div_v_time_avg / c.mean_abs_div_v_time_avg,
                c.max_rel_density_error / u.max_rel_density_error, u.max_rel_density_error / c.max_rel_density_error,
                100 * (c.kinetic_energy_end - u.kinetic_energy_end) / u.kinetic_energy_end);
  }
}

void make_drop_pictures(const std::filesystem::path& out, const DropResults& results, Real frame_every, Real t_end) {
  std::vector<std::string> csvs;
  for (const auto& [label, r] : results) csvs.push_back((out / label / "diagnostics.csv").string() + ":" + label);
  const auto chart = [&](const std::string& y, const std::string& ylabel, const std::string& png, bool logy,
                         const std::string& title) {
    std::vector<std::string> args;
    for (const auto& c : csvs) args.insert(args.end(), {"--csv", c});
    args.insert(args.end(), {"--x", "t", "--y", y, "--ylabel", ylabel, "--title", title, "--out", (out / png).string()});
    if (logy) args.push_back("--logy");
    run_python("charts.py", args, false);
  };
  chart("mean_abs_div_v", "mean |div v|  [1/s]", "div_v.png", true, "water drop: mean velocity divergence (paper Fig. 8)");
  chart("max_rel_density_error", "max |rho - rho0| / rho0", "density_error.png", false,
        "water drop: maximum density error (paper Fig. 9)");
  chart("kinetic_energy", "kinetic energy  [J/m]", "kinetic_energy.png", false, "water drop: kinetic energy (paper Fig. 10)");
  for (const auto& [label, r] : results) {
    const std::string csv = (out / label / "diagnostics.csv").string();
    run_python("charts.py",
               {"--csv", csv, "--x", "t", "--y", "semi_axis_x", "--y-extra", "semi_axis_x_exact:a exact", "--y-extra",
                "semi_axis_y", "--y-extra", "semi_axis_y_exact:b exact", "--ylabel", "semi-axis", "--title",
                "water drop (" + label + "): semi-axes vs exact ellipse", "--out",
                (out / ("semi_axes_" + label + ".png")).string()},
               false);
    const std::string pvd = (out / label / "drop.pvd").string();
    // frames at t = 0, the first squeeze (t ~ 0.012), the first maximum along x (t ~ 0.035), the end
    std::vector<std::string> args = {pvd, "--grid", "2x2", "--frames"};
    for (Real t : {0.0, 0.012, 0.035}) {
      const long k = std::lround(std::min(t, t_end) / frame_every);
      args.push_back(std::to_string(k));
    }
    args.insert(args.end(), {"-1", "--array", "pressure", "--out", (out / ("frames_" + label + ".png")).string()});
    run_python("render_particles.py", args, true);
  }
}

}  // namespace sphark
