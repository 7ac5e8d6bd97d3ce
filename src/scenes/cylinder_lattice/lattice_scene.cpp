#include "sphark/scenes/cylinder_lattice/lattice_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <sstream>

#include "ensemble_case.hpp"
#include "sphark/io/csv_writer.hpp"
#include "sphark/io/visualise.hpp"
#include "sphark/run/run_outputs.hpp"

namespace sphark {

namespace {

GhostMap parse_map(const std::string& name) { return name == "mirror" ? GhostMap::Mirror : GhostMap::DensityPreserving; }

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

// One single/medium run: a VTK series of the real particles, per frame the ghosts and a fields
// CSV. The penetration / accumulation roots (seed 004, eq. 37) end the run at their root time.
class LatticeRun final : public SceneRun {
 public:
  LatticeRun(const LatticeRunConfig& cfg) : cfg_(cfg), sys_(cfg.particles, lattice_params(cfg.params, cfg.particles)) {
    cpu0_ = process_cpu_seconds();
  }
  OdeSystem& system() override { return sys_; }
  const StateLayout& layout() const override { return sys_.layout(); }
  std::vector<Real> initial_state() override {
    std::vector<Real> y(sys_.size(), 0.0);  // at rest
    const std::vector<Real> x0 = initial_positions(cfg_);
    std::copy(x0.begin(), x0.end(), y.begin() + static_cast<std::ptrdiff_t>(sys_.position_offset()));
    return y;
  }
  StepperOptions stepper(const CoreOptions&, std::string_view) override { return cfg_.stepper; }
  std::vector<std::string> columns() const override {
    return {"t", "kinetic_energy", "min_ghost_h_over_h_ref", "wall_force_x", "wall_force_y", "steps", "rhs_evals"};
  }
  std::vector<Real> diagnostics(Real t, const Real* y, const StepperStats& st) override;
  ParticleFrame frame(Real t, const Real* y) override;
  bool finished(Real) override { return event(sampled_g_); }
  bool root(Real, const std::vector<int>& found) override {
    Real g[2] = {1, 1};
    if (!found.empty() && found[0] != 0) g[0] = 0; else g[1] = 0;
    return event(g);
  }
  void settings(TimeLoopSettings& s) override {
    s.frames_basename = "lattice";
    s.progress_interval = 10;
    frame_every_ = s.frame_every;
    dir_ = s.frames_dir;
    ghosts_.emplace(dir_, "ghosts");  // frame k of the ghosts goes with lattice_k
    if (s.restart) ghosts_->restore(ghost_frames(s.restart->text("frames"), dir_));
  }
  LatticeRunResult result(const TimeLoopResult& loop) const;

 private:
  bool event(const Real* g) {
    if (g[0] <= 0) reason_ = "penetration";
    else if (g[1] <= 0) reason_ = "accumulation";
    return !reason_.empty();
  }

  LatticeRunConfig cfg_;
  LatticeSystem sys_;
  std::optional<ResumableVtkSeries> ghosts_;
  std::filesystem::path dir_;
  Real frame_every_ = 0, sampled_g_[2] = {1, 1};
  std::vector<Real> wrapped_;
  std::string reason_;
  double cpu0_ = 0;
};

std::vector<Real> LatticeRun::diagnostics(Real t, const Real* y, const StepperStats& st) {
  const LatticeParams& p = sys_.params();
  const int rc = sys_.prepare(y);  // density, h, ghosts of this state
  if (rc != 0 || sys_.roots(t, y, sampled_g_) != 0) sampled_g_[0] = sampled_g_[1] = 1;
  Real ke = 0;
  const Real* v = y + sys_.velocity_offset();
  for (std::size_t i = 0; i < 2 * sys_.particles(); ++i) ke += 0.5 * p.mass * v[i] * v[i];
  const Vec<2> f = rc == 0 ? sys_.wall_force() : Vec<2>(NAN, NAN);
  return {t, ke, rc == 0 ? sys_.min_ghost_h() / p.h_ref : NAN, f[0], f[1], static_cast<Real>(st.steps),
          static_cast<Real>(st.rhs_evals)};
}

ParticleFrame LatticeRun::frame(Real t, const Real* y) {
  if (sys_.prepare_if_moved(y) != 0) throw std::runtime_error("lattice frame at t=" + std::to_string(t) + ": " + sys_.last_error());
  ParticleFrame g;
  g.dim = 2;
  g.count = sys_.ghost_count();
  g.positions = sys_.all_positions().data() + 2 * sys_.particles();
  g.arrays = {{"velocity", sys_.ghosts().velocities(), 2},
              {"density", sys_.density().data() + sys_.particles(), 1},
              {"h", sys_.smoothing_length().data() + sys_.particles(), 1}};
  if (g.count > 0) ghosts_->write(g, t);
  char name[64];  // fields_NNNN.csv on the frame grid, fields_end.csv at an event or a failure
  const Real k = std::round(t / frame_every_);
  if (std::abs(t - k * frame_every_) <= 1e-9 * frame_every_)
    std::snprintf(name, sizeof name, "fields_%04ld.csv", static_cast<long>(k));
  else
    std::snprintf(name, sizeof name, "fields_end.csv");
  wrapped_.resize(2 * sys_.particles());
  lattice_box(sys_.params()).wrap_all(y + sys_.position_offset(), sys_.particles(), wrapped_.data());
  write_file_atomically(dir_ / name, "# t=" + std::to_string(t) + "\n" + fields_csv(sys_, y, wrapped_));
  ParticleFrame f;
  f.dim = 2;
  f.count = sys_.particles();
  f.positions = wrapped_.data();
  f.arrays = {{"velocity", y + sys_.velocity_offset(), 2},
              {"density", sys_.density().data(), 1},
              {"h", sys_.smoothing_length().data(), 1},
              {"pressure", sys_.pressure().data(), 1}};
  return f;
}

LatticeRunResult LatticeRun::result(const TimeLoopResult& loop) const {
  LatticeRunResult r;
  r.reason = reason_;
  r.t_max = loop.t_reached;
  r.stats = loop.stats;
  r.rhs_calls = loop.stats.rhs_evals;
  if (loop.status == TimeLoopStatus::Reached) r.reason = "t_end";
  if (loop.status == TimeLoopStatus::Failed) r.reason = "failure: " + loop.failure;
  if (loop.status == TimeLoopStatus::Stopped) r.reason = "stopped";
  r.cpu_seconds = process_cpu_seconds() - cpu0_;
  return r;
}

std::string summary_csv(const std::vector<CylinderLatticeScene::Outcome>& runs) {
  std::ostringstream os;
  os << "map,t_max,reason,steps,rhs_calls,cpu_seconds,wall_seconds\n";
  for (const auto& r : runs)
    os << r.map << ',' << r.result.t_max << ",\"" << r.result.reason << "\"," << r.result.stats.steps << ','
       << r.result.rhs_calls << ',' << r.result.cpu_seconds << ',' << r.wall_seconds << '\n';
  return os.str();
}

}  // namespace

CylinderLatticeScene::CylinderLatticeScene()
    : v0s_{0.05, 0.10, 0.15, 0.20, 0.25, 0.30, 0.35, 0.40, 0.45, 0.50, 0.55, 0.60, 0.65, 0.70, 0.75} {}

std::string CylinderLatticeScene::description() const {
  return "flow through a periodic lattice of cylinders with ghost walls (seed 004 §8)";
}

void CylinderLatticeScene::set_defaults(CoreOptions& core) {
  core.out = "out/cylinder_lattice";
  core.t_end = 10;
  core.stepper = "leapfrog";
  core.output_every = 0;
  core.threads = 0;
}

std::filesystem::path CylinderLatticeScene::subdirectory(const std::string& map) const {
  return case_ == "single" ? "single_" + map : map;
}

void CylinderLatticeScene::check_restart_run(const OptionParser& p, const std::string& run) const {
  if (map_ != "both" && map_ != run) p.fail("--map", map_ + " contradicts the checkpoint (map " + run + ")");
}

std::unique_ptr<SceneRun> CylinderLatticeScene::make_run(const std::string& map, const CoreOptions&) {
  LatticeRunConfig cfg = run_;
  cfg.params.map = parse_map(map);
  return std::make_unique<LatticeRun>(cfg);
}

// The same run with fewer particles and no relaxation (it moves them, it does not add memory).
std::unique_ptr<SceneRun> CylinderLatticeScene::make_probe_run(const std::string& map, const CoreOptions&,
                                                               Real particles) {
  LatticeRunConfig cfg = run_;
  cfg.params.map = parse_map(map);
  cfg.particles = std::min(cfg.particles, static_cast<std::size_t>(particles));
  cfg.relax_iterations = 0;
  return std::make_unique<LatticeRun>(cfg);
}

void CylinderLatticeScene::finished(const std::string& map, SceneRun& r, const TimeLoopResult& result) {
  outcomes_.push_back({map, static_cast<LatticeRun&>(r).result(result), result.wall_seconds});
  const Outcome& o = outcomes_.back();
  std::printf("%-22s t_max %.4g  reason %s  rhs %ld  steps %ld  cpu %.1f s  wall %.1f s\n",
              (case_ + " " + map).c_str(), o.result.t_max, o.result.reason.c_str(), o.result.rhs_calls,
              o.result.stats.steps, o.result.cpu_seconds, o.wall_seconds);
}

int CylinderLatticeScene::report(const CoreOptions& core, const std::vector<std::string>& runs, bool all_ok) {
  if (outcomes_.empty()) return 0;
  if (case_ == "single") {
    write_file_atomically(core.out / subdirectory(runs.front()) / "summary.csv", summary_csv(outcomes_));
    return 0;
  }
  write_file_atomically(core.out / (runs.size() > 1 ? "summary.csv" : "summary_" + runs[0] + ".csv"),
                        summary_csv(outcomes_));
  if (!all_ok || !core.render) return 0;
  std::vector<std::string> args{"fig9", core.out.string()};
  for (const auto& m : runs) args.push_back(m);
  if (!run_python("cylinder_lattice.py", args, false)) return 1;
  for (const auto& m : runs)  // the VTK series' last frame: speed, v_y and pressure
    run_python("render_particles.py",
               {(core.out / m / "lattice.pvd").string(), "--grid", "1x2", "--frame", "-1", "--arrays", "velocity",
                "pressure", "--out", (core.out / m / "final.png").string()},
               true);
  return 0;
}

std::optional<int> CylinderLatticeScene::run_instead(const CoreOptions& core) {
  if (case_ != "ensemble") return std::nullopt;
  return run_lattice_ensemble(run_, maps_, v0s_, seeds_, core);
}

// per map: the real particles coloured by velocity
std::vector<Scene::ParaViewStateFile> CylinderLatticeScene::paraview_states(const std::vector<std::string>& runs) const {
  std::vector<ParaViewStateFile> states;
  for (const std::string& m : runs) states.push_back({subdirectory(m) / "view.pvsm", {{"lattice.pvd", "velocity"}}});
  return states;
}

}  // namespace sphark
