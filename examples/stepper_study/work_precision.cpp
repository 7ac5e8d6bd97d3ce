// The work-precision matrix: every method x tolerance (adaptive, with and without the CFL cap)
// and every fixed CFL number, against the exact solution and against a reference run.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "study.hpp"

namespace sphark {
namespace {

std::string clean(std::string s) {  // one CSV cell: no commas, quotes or newlines
  for (char& ch : s)
    if (ch == ',' || ch == '"' || ch == '\n' || ch == '\r') ch = ';';
  return s;
}

class RowWriter {
 public:
  explicit RowWriter(const std::filesystem::path& path) : f_(path) {
    if (!f_) throw std::runtime_error("cannot write " + path.string());
    f_ << "scene,method,rtol,dt,cpu_s,rhs_evals,steps,rejected,error,mode,cfl,time_error,position_error,"
          "rhs_evals_implicit,mean_cfl,status,failure\n";
  }
  void row(const StudyScene& scene, const StudyCase& c, const StudyResult& r, const StudyErrors& e) {
    const StepperStats& st = r.stats;
    const Real mean_dt = st.steps > 0 ? r.t_reached / static_cast<Real>(st.steps) : 0;
    const Real dt = c.mode == StudyMode::Fixed ? c.cfl * scene.cfl_unit() : mean_dt;
    char buf[512];
    std::snprintf(buf, sizeof buf, "%s,%s,%.3g,%.9g,%.6g,%ld,%ld,%ld,%.9g,%s,%.6g,%.9g,%.9g,%ld,%.6g,%s,", scene.name().c_str(),
                  c.method.c_str(), c.mode == StudyMode::Fixed ? 0.0 : c.rtol, dt, r.cpu_seconds, st.rhs_evals, st.steps,
                  st.attempts - st.steps, e.exact, to_string(c.mode).c_str(), c.mode == StudyMode::Fixed ? c.cfl : 0.0,
                  e.time, e.position, st.rhs_evals_implicit, mean_dt / scene.cfl_unit(), r.status.c_str());
    f_ << buf << clean(r.failure) << "\n";
    f_.flush();
  }

 private:
  std::ofstream f_;
};

void print(const StudyCase& c, const StudyResult& r, const StudyErrors& e) {
  std::printf("%-32s %-8s rtol %-7.0e cfl %-5.3g  %-9s cpu %7.2f s  rhs %8ld  steps %7ld  rej %5ld  err %.3e  time-err %.3e\n",
              c.method.c_str(), to_string(c.mode).c_str(), c.rtol, c.cfl, r.status.c_str(), r.cpu_seconds,
              r.stats.rhs_evals, r.stats.steps, r.stats.attempts - r.stats.steps, e.exact, e.time);
  std::fflush(stdout);
}

}  // namespace

std::string unsupported(const StudyScene& scene, const std::string& method) {
  const std::unique_ptr<StudyProblem> p = scene.build();
  if ((method == "leapfrog" || method == "leapfrog-rev") && p->system().position_size() == 0)
    return "the scene's particles do not move (no position block)";
  if (method == "ark-imex" && !p->system().has_stiff_diagonal()) return "the scene has no stiff part";
  return {};
}

bool run_work_precision(const StudyScene& scene, const StudySettings& s) {
  std::printf("reference: %s rtol %.0e (check: %s rtol %.0e)\n", s.reference.method.c_str(), s.reference.rtol,
              s.reference_check.method.c_str(), s.reference_check.rtol);
  const StudyResult ref = run_study_case(scene, s.reference, s.limits);
  if (!ref.ok()) {
    std::fprintf(stderr, "stepper_study: reference run failed: %s %s\n", ref.status.c_str(), ref.failure.c_str());
    return false;
  }
  const StudyResult check = run_study_case(scene, s.reference_check, s.limits);
  RowWriter ref_csv(s.out / "reference.csv");
  const StudyErrors ref_err = study_errors(scene, ref, ref);
  ref_csv.row(scene, s.reference, ref, ref_err);
  const StudyErrors check_err = study_errors(scene, check, ref);
  ref_csv.row(scene, s.reference_check, check, check_err);
  print(s.reference, ref, ref_err);
  print(s.reference_check, check, check_err);

  RowWriter csv(s.out / "work_precision.csv");
  const auto run = [&](const StudyCase& c) {
    if (const std::string why = unsupported(scene, c.method); !why.empty()) {
      std::printf("%-32s skipped: %s\n", c.method.c_str(), why.c_str());
      return;
    }
    const StudyResult r = run_study_case(scene, c, s.limits);
    const StudyErrors e = study_errors(scene, r, ref);
    print(c, r, e);
    csv.row(scene, c, r, e);
  };
  for (const std::string& m : s.adaptive_methods)
    for (StudyMode mode : s.adaptive_modes)
      for (Real rtol : s.rtols) run({m, mode, rtol, 0});
  for (const std::string& m : s.fixed_methods)
    for (Real cfl : s.fixed_cfls) run({m, StudyMode::Fixed, 0, cfl});
  for (const std::string& m : s.leapfrog_methods)
    for (Real cfl : s.leapfrog_cfls) run({m, StudyMode::Fixed, 0, cfl});
  return true;
}

void run_stability(const StudyScene& scene, const StudySettings& s) {
  std::ofstream f(s.out / "stability.csv");
  if (!f) throw std::runtime_error("cannot write " + (s.out / "stability.csv").string());
  f << "scene,method,cfl_stable,cfl_unstable,horizon,energy_tolerance,trials,cpu_s,unstable_reason\n";
  const Real horizon = s.stability.horizon > 0 ? s.stability.horizon : scene.t_end();
  for (const std::string& m : s.stability_methods) {
    if (const std::string why = unsupported(scene, m); !why.empty()) {
      std::printf("stability %-32s skipped: %s\n", m.c_str(), why.c_str());
      continue;
    }
    const StabilityLimit L = find_stability_limit(scene, m, s.stability);
    std::printf("stability %-32s CFL stable %.4g unstable %.4g  (%d trials, cpu %.1f s)  %s\n", m.c_str(), L.cfl_stable,
                L.cfl_unstable, L.trials, L.cpu_seconds, L.unstable_reason.c_str());
    std::fflush(stdout);
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s,%s,%.6g,%.6g,%.6g,%.3g,%d,%.4g,", scene.name().c_str(), m.c_str(), L.cfl_stable,
                  L.cfl_unstable, horizon, s.stability.energy_tolerance, L.trials, L.cpu_seconds);
    f << buf << clean(L.unstable_reason) << "\n";
    f.flush();
  }
}

}  // namespace sphark
