// The work-precision matrix: every method x tolerance (adaptive, with and without the CFL cap)
// and every fixed CFL number, against the exact solution and against a reference run. Tables
// are rewritten atomically after every row; SIGINT/SIGTERM stop the case in progress at its next
// RHS evaluation (it leaves no row); --resume keeps
// the rows of an earlier run and skips their cases.
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <set>
#include <stdexcept>

#include "sphark/core/profile.hpp"
#include "sphark/io/csv_writer.hpp"
#include "sphark/run/signals.hpp"
#include "study.hpp"

namespace sphark {
namespace {

std::string clean(std::string s) {  // one CSV cell: no commas, quotes or newlines
  for (char& ch : s)
    if (ch == ',' || ch == '"' || ch == '\n' || ch == '\r') ch = ';';
  return s;
}

// A CSV table kept in memory and rewritten atomically after every row (a killed or interrupted
// study leaves complete rows only). With `resume`, the rows of an existing file are kept and
// has(key) says which cases they cover.
class Table {
 public:
  using KeyOf = std::string (*)(const std::string& line);
  Table(std::filesystem::path path, std::string header, bool resume, KeyOf key_of)
      : path_(std::move(path)), header_(std::move(header)), key_of_(key_of) {
    text_ = header_;
    if (!resume || !std::filesystem::exists(path_)) {
      write_file_atomically(path_, text_);  // the header: an interrupted study leaves a table
      return;
    }
    std::ifstream in(path_);
    std::string line;
    std::getline(in, line);
    if (line + "\n" != header_) throw std::runtime_error("--resume: " + path_.string() + " has other columns");
    while (std::getline(in, line))
      if (!line.empty()) {
        keys_.insert(key_of_(line));
        text_ += line + "\n";
      }
  }
  bool has(const std::string& key) const { return keys_.count(key) > 0; }
  std::size_t rows() const { return keys_.size(); }
  void add(const std::string& line) {  // without its newline
    ScopedPhase phase(Phase::Output);
    keys_.insert(key_of_(line));
    text_ += line + "\n";
    write_file_atomically(path_, text_);
  }

 private:
  std::filesystem::path path_;
  std::string header_, text_;
  KeyOf key_of_;
  std::set<std::string> keys_;
};

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t end; (end = line.find(',', start)) != std::string::npos; start = end + 1)
    out.push_back(line.substr(start, end - start));
  out.push_back(line.substr(start));
  return out;
}

const char* kWorkPrecisionHeader =
    "scene,method,rtol,dt,cpu_s,rhs_evals,steps,rejected,error,mode,cfl,time_error,position_error,"
    "rhs_evals_implicit,mean_cfl,status,failure\n";

// The first cells of a work-precision row; (method, mode, rtol, cfl) identify the case.
std::string case_key(const StudyCase& c) {
  char buf[256];
  std::snprintf(buf, sizeof buf, ",%s,%.3g,%s,%.6g", c.method.c_str(), c.mode == StudyMode::Fixed ? 0.0 : c.rtol,
                to_string(c.mode).c_str(), c.mode == StudyMode::Fixed ? c.cfl : 0.0);
  return buf;
}

std::string row_text(const StudyScene& scene, const StudyCase& c, const StudyResult& r, const StudyErrors& e) {
  const StepperStats& st = r.stats;
  const Real mean_dt = st.steps > 0 ? r.t_reached / static_cast<Real>(st.steps) : 0;
  const Real dt = c.mode == StudyMode::Fixed ? c.cfl * scene.cfl_unit() : mean_dt;
  char buf[512];
  std::snprintf(buf, sizeof buf, "%s,%s,%.3g,%.9g,%.6g,%ld,%ld,%ld,%.9g,%s,%.6g,%.9g,%.9g,%ld,%.6g,%s,", scene.name().c_str(),
                c.method.c_str(), c.mode == StudyMode::Fixed ? 0.0 : c.rtol, dt, r.cpu_seconds, st.rhs_evals, st.steps,
                st.attempts - st.steps, e.exact, to_string(c.mode).c_str(), c.mode == StudyMode::Fixed ? c.cfl : 0.0,
                e.time, e.position, st.rhs_evals_implicit, mean_dt / scene.cfl_unit(), r.status.c_str());
  return buf + clean(r.failure);
}

// (method, rtol, mode, cfl) of a row: cells 2, 3, 10, 11 (the same text as case_key).
std::string row_key(const std::string& line) {
  const std::vector<std::string> c = cells(line);
  return c.size() > 10 ? "," + c[1] + "," + c[2] + "," + c[9] + "," + c[10] : line;
}

std::string method_key(const std::string& line) {  // stability.csv: the method
  const std::vector<std::string> c = cells(line);
  return c.size() > 1 ? c[1] : line;
}

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
  Table csv(s.out / "work_precision.csv", kWorkPrecisionHeader, s.resume, row_key);
  if (s.resume) std::printf("--resume: %zu rows of work_precision.csv kept, their cases skipped\n", csv.rows());
  std::printf("reference: %s rtol %.0e (check: %s rtol %.0e)\n", s.reference.method.c_str(), s.reference.rtol,
              s.reference_check.method.c_str(), s.reference_check.rtol);
  const StudyResult ref = run_study_case(scene, s.reference, s.limits);
  if (ref.status == "stopped") return true;  // SIGINT/SIGTERM: main reports it
  if (!ref.ok()) {
    std::fprintf(stderr, "stepper_study: reference run failed: %s %s\n", ref.status.c_str(), ref.failure.c_str());
    return false;
  }
  const StudyResult check = run_study_case(scene, s.reference_check, s.limits);
  if (check.status == "stopped") return true;
  Table ref_csv(s.out / "reference.csv", kWorkPrecisionHeader, false, row_key);
  const StudyErrors ref_err = study_errors(scene, ref, ref);
  ref_csv.add(row_text(scene, s.reference, ref, ref_err));
  const StudyErrors check_err = study_errors(scene, check, ref);
  ref_csv.add(row_text(scene, s.reference_check, check, check_err));
  print(s.reference, ref, ref_err);
  print(s.reference_check, check, check_err);

  // false after SIGINT/SIGTERM: the rows so far are written, the rest is left for --resume
  int done = 0;
  const auto run = [&](const StudyCase& c) {
    if (stop_requested()) return false;
    if (csv.has(case_key(c))) return true;
    if (const std::string why = unsupported(scene, c.method); !why.empty()) {
      std::printf("%-32s skipped: %s\n", c.method.c_str(), why.c_str());
      return true;
    }
    const StudyResult r = run_study_case(scene, c, s.limits);
    if (r.status == "stopped") return false;  // cut short: no row (--resume runs it again)
    const StudyErrors e = study_errors(scene, r, ref);
    print(c, r, e);
    csv.add(row_text(scene, c, r, e));
    if (++done == s.raise_sigint_after) std::raise(SIGINT);  // testing aid: the real handler
    return true;
  };
  for (const std::string& m : s.adaptive_methods)
    for (StudyMode mode : s.adaptive_modes)
      for (Real rtol : s.rtols)
        if (!run({m, mode, rtol, 0})) return true;
  for (const std::string& m : s.fixed_methods)
    for (Real cfl : s.fixed_cfls)
      if (!run({m, StudyMode::Fixed, 0, cfl})) return true;
  for (const std::string& m : s.leapfrog_methods)
    for (Real cfl : s.leapfrog_cfls)
      if (!run({m, StudyMode::Fixed, 0, cfl})) return true;
  return true;
}

void run_stability(const StudyScene& scene, const StudySettings& s) {
  Table f(s.out / "stability.csv",
          "scene,method,cfl_stable,cfl_unstable,horizon,energy_tolerance,trials,cpu_s,unstable_reason\n", s.resume,
          method_key);
  const Real horizon = s.stability.horizon > 0 ? s.stability.horizon : scene.t_end();
  for (const std::string& m : s.stability_methods) {
    if (stop_requested()) return;
    if (f.has(m)) continue;
    if (const std::string why = unsupported(scene, m); !why.empty()) {
      std::printf("stability %-32s skipped: %s\n", m.c_str(), why.c_str());
      continue;
    }
    StabilityLimit L;
    try {
      L = find_stability_limit(scene, m, s.stability);
    } catch (const StopRequested&) {
      return;  // a trial was cut short: no row for this method
    }
    std::printf("stability %-32s CFL stable %.4g unstable %.4g  (%d trials, cpu %.1f s)  %s\n", m.c_str(), L.cfl_stable,
                L.cfl_unstable, L.trials, L.cpu_seconds, L.unstable_reason.c_str());
    std::fflush(stdout);
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s,%s,%.6g,%.6g,%.6g,%.3g,%d,%.4g,", scene.name().c_str(), m.c_str(), L.cfl_stable,
                  L.cfl_unstable, horizon, s.stability.energy_tolerance, L.trials, L.cpu_seconds);
    f.add(buf + clean(L.unstable_reason));
  }
}

}  // namespace sphark
