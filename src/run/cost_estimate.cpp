#include "sphark/run/cost_estimate.hpp"

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "sphark/integrate/stepper.hpp"
#include "sphark/run/signals.hpp"

#if defined(__SANITIZE_ADDRESS__)
extern "C" std::size_t __sanitizer_get_current_allocated_bytes();
#endif

namespace sphark {
namespace {

std::optional<double> read_number_file(const char* path) {
  std::ifstream in(path);
  std::string word;
  if (!(in >> word)) return std::nullopt;
  return parse_byte_size(word);  // "max" (no limit) reads as nullopt
}

std::string read_all(const char* path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Checkpoint copies of the state at a save: Checkpoint::y, its encoding, the stepper's resume data.
constexpr double kCheckpointStateCopies = 3;

}  // namespace

std::optional<double> parse_byte_size(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !std::isfinite(v) || v < 0) return std::nullopt;
  const std::string unit(end);
  double scale = 1;
  if (unit == "K" || unit == "k") scale = 1e3;
  else if (unit == "M") scale = 1e6;
  else if (unit == "G") scale = 1e9;
  else if (unit == "T") scale = 1e12;
  else if (!unit.empty()) return std::nullopt;
  return v * scale;
}

std::optional<double> parse_mem_available(const std::string& meminfo) {
  std::istringstream in(meminfo);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("MemAvailable:", 0) != 0) continue;
    std::istringstream fields(line.substr(13));
    double kb = 0;
    std::string unit;
    if (fields >> kb >> unit && unit == "kB" && kb >= 0) return kb * 1024;
  }
  return std::nullopt;
}

std::optional<double> memory_available_bytes() {
  std::optional<double> avail = parse_mem_available(read_all("/proc/meminfo"));
  const auto lower = [&avail](std::optional<double> v) {
    if (v) avail = avail ? std::min(*avail, *v) : *v;
  };
  const auto max = read_number_file("/sys/fs/cgroup/memory.max"), used = read_number_file("/sys/fs/cgroup/memory.current");
  if (max && used) lower(std::max(0.0, *max - *used));
  if (const char* limit = std::getenv("SPHARK_MEMORY_LIMIT")) lower(parse_byte_size(limit));
  return avail;
}

double heap_bytes_in_use() {
#if defined(__SANITIZE_ADDRESS__)
  return static_cast<double>(__sanitizer_get_current_allocated_bytes());
#else
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks) + static_cast<double>(m.hblkhd);
#endif
}

ProbeMeasurement measure_probe(const std::function<ProbeSubject()>& build, Real t_end) {
  ProbeMeasurement r;
  const double before = heap_bytes_in_use();
  ProbeSubject s = build();
  r.particles = s.particles;
  r.state_bytes = static_cast<double>(s.y0.size() * sizeof(Real));
  std::vector<Real> y = s.y0;
  StepperOptions o = s.stepper;
  o.max_steps = std::min(o.max_steps, 200L);
  // SIGINT/SIGTERM end the probe at its next evaluation (the caller then stops the set-up)
  if (!o.interrupt) o.interrupt = [] { return stop_requested() != 0; };
  const Real stable = s.system->max_stable_dt(0, y.data(), nullptr);
  const Real dt = o.fixed_dt > 0 ? o.fixed_dt : o.cfl_safety * stable;
  const Real unit = std::isfinite(dt) && dt > 0 ? dt : 1e-7 * t_end;
  try {
    // one step of warm-up (neighbour lists, ARKODE's initial step), then three timed ones
    auto stepper = make_stepper(*s.system, o, 0, y.data());
    Real t = 0;
    if (stepper->advance(std::min(t_end, unit), y.data(), t) == AdvanceStatus::Reached && t < t_end) {
      const long before_steps = stepper->stats().steps;
      const auto start = std::chrono::steady_clock::now();
      stepper->advance(std::min(t_end, 4 * unit), y.data(), t);
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const long timed = stepper->stats().steps - before_steps;
      if (timed > 0) r.seconds_per_step = wall / static_cast<double>(timed);
    }
    r.steps = stepper->stats().steps;
    if (s.diagnostics) s.diagnostics(t, y.data());
    r.heap_bytes = std::max(0.0, heap_bytes_in_use() - before);
  } catch (const std::exception&) {  // the run itself reports it; the memory so far still counts
    r.heap_bytes = std::max(0.0, heap_bytes_in_use() - before);
  }
  return r;
}

CostEstimate estimate_memory(double particles, const ProbeMeasurement& probe) {
  CostEstimate e;
  e.particles = particles;
  e.probe_particles = probe.particles;
  if (probe.particles > 0)
    e.bytes_per_particle = (probe.heap_bytes + kCheckpointStateCopies * probe.state_bytes) / probe.particles;
  e.bytes = particles * e.bytes_per_particle;
  e.available = memory_available_bytes();
  return e;
}

void estimate_time(CostEstimate& e, OdeSystem& system, const StepperOptions& so, Real t0, const Real* y0, Real t_end,
                   Real longest_step, const ProbeMeasurement& probe) {
  const bool leapfrog = so.method == "leapfrog" || so.method == "leapfrog-rev";
  Real dt = so.fixed_dt;
  if (!(dt > 0)) {
    // Capped adaptive runs and the leapfrog: the stable step (capped: a lower bound on the steps).
    // Uncapped explicit runs: an estimate from the stability reach of the tables -- none of SUNDIALS
    // 6.4.1 is stable beyond 6.3 CFL units (docs/time_integration.md), below kUncappedReach stable
    // steps for a scheme's CFL number >= 0.2 -- not a bound (the stable step may grow).
    constexpr Real kUncappedReach = 32;
    const Real stable = system.max_stable_dt(t0, y0, nullptr);
    dt = leapfrog || so.cap_by_stability ? so.cfl_safety * stable : kUncappedReach * stable;
    if (so.max_dt > 0) dt = std::min(dt, so.max_dt);
    e.steps_at_least = !leapfrog && so.cap_by_stability;
  }
  if (longest_step > 0 && dt > longest_step) {  // the time loop lands on every row: no step is longer
    dt = longest_step;
    e.steps_at_least = true;
  }
  if (!(dt > 0) || !std::isfinite(dt)) return;
  e.first_step = dt;
  e.steps = std::max(1.0, std::ceil((t_end - t0) / dt));
  if (probe.particles > 0 && std::isfinite(probe.seconds_per_step))
    e.seconds = e.steps * probe.seconds_per_step * std::max(1.0, e.particles / probe.particles);
}

std::string bytes_text(double b) {
  char buf[32];
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB"};
  int u = 0;
  while (b >= 1000 && u < 5) b /= 1000, ++u;
  if (b >= 1000) std::snprintf(buf, sizeof buf, "%.3g %s", b, units[u]);
  else std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", b, units[u]);
  return buf;
}

std::string duration_text(double s) {
  char buf[40];
  if (!std::isfinite(s)) return "?";
  if (s < 120) std::snprintf(buf, sizeof buf, "%.2g s", s);
  else if (s < 7200) std::snprintf(buf, sizeof buf, "%.2g min", s / 60);
  else if (s < 2 * 86400) std::snprintf(buf, sizeof buf, "%.2g h", s / 3600);
  else if (s < 2 * 365.25 * 86400) std::snprintf(buf, sizeof buf, "%.3g days", s / 86400);
  else std::snprintf(buf, sizeof buf, "%.3g years", s / (365.25 * 86400));
  return buf;
}

namespace {
std::string count_text(double n) {
  char buf[32];
  std::snprintf(buf, sizeof buf, n < 1e7 ? "%.0f" : "%.3g", n);
  return buf;
}
}  // namespace

std::string memory_refusal(const CostEstimate& e) {
  if (!std::isfinite(e.bytes)) return "more particles than can be counted (" + count_text(e.particles) + ")";
  return count_text(e.particles) + " particles need ~" + bytes_text(e.bytes) + " (" + bytes_text(e.bytes_per_particle) +
         " each, measured on a " + count_text(e.probe_particles) + "-particle probe); " +
         (e.available ? bytes_text(*e.available) : std::string("?")) + " available";
}

std::string cost_line(const std::string& program, const std::string& run, const CostEstimate& e) {
  std::string line = program + ": " + run + " run";
  line += e.longer_than_a_day() ? " will take LONGER THAN A DAY: predicted " : ": predicted ";
  line += count_text(e.particles) + " particles, " + bytes_text(e.bytes);
  if (e.available) line += " of " + bytes_text(*e.available) + " available";
  if (std::isfinite(e.steps)) {
    char dt[32];
    std::snprintf(dt, sizeof dt, "%.3g", e.first_step);
    line += std::string(", ") + (e.steps_at_least ? ">= " : "") + count_text(e.steps) + " steps (first dt " + dt + ")";
  }
  if (std::isfinite(e.seconds)) line += (e.steps_at_least ? ", >= " : ", ~") + duration_text(e.seconds);
  return line;
}

}  // namespace sphark
