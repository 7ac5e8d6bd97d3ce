#include "sphark/scenes/cylinder_lattice/lattice_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <optional>
#include <sstream>

#include "ensemble_case.hpp"
#include "sphark/diagnostics/step_levels.hpp"
#include "sphark/io/csv_writer.hpp"
#include "sphark/io/visualise.hpp"
#include "sphark/parallel/distributed_particles.hpp"
#include "sphark/parallel/global_state.hpp"
#include "sphark/schemes/ghost_wcsph/ghost_migration.hpp"
#include "sphark/run/migration_step.hpp"
#include "sphark/run/run_outputs.hpp"

namespace sphark {

namespace {

GhostMap parse_map(const std::string& name) { return name == "mirror" ? GhostMap::Mirror : GhostMap::DensityPreserving; }

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Particle fields as CSV text (for the Fig. 9 interpolation in vis/cylinder_lattice.py): x the
// positions wrapped into the box, v, rho, h of n particles (2, 2, 1, 1 values each).
std::string fields_csv(const Real* x, const Real* v, const Real* rho, const Real* h, std::size_t n) {
  std::ostringstream os;
  os.precision(10);
  os << "x,y,vx,vy,rho,h\n";
  for (std::size_t a = 0; a < n; ++a)
    os << x[2 * a] << ',' << x[2 * a + 1] << ',' << v[2 * a] << ',' << v[2 * a + 1] << ',' << rho[a] << ',' << h[a] << '\n';
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
  // A world with MPI: a distributed run (RCB domains, migrations on schedule_; docs/scaling.md,
  // "The lattice").
  LatticeRun(const LatticeRunConfig& cfg, Communicator world = {})
      : cfg_(cfg), sys_(cfg.particles, lattice_params(cfg.params, cfg.particles)), world_(std::move(world)) {
    cpu0_ = process_cpu_seconds();
    if (!world_.distributed()) return;
    const std::vector<Real> y_all = whole_initial_state();
    parts_.emplace(world_, y_all.data() + sys_.position_offset(), sys_.particles(), lattice_box(sys_.params()));
    y_ = share_of(sys_.layout(), y_all, parts_->ids());
    sys_.distribute(world_, parts_->ids());
  }
  OdeSystem& system() override { return sys_; }
  const StateLayout& layout() const override { return sys_.layout(); }
  std::vector<Real> initial_state() override { return parts_ ? y_ : whole_initial_state(); }
  StepperOptions stepper(const CoreOptions&, std::string_view) override {
    StepperOptions o = cfg_.stepper;
    o.communicator = world_;
    return o;
  }
  std::vector<std::string> columns() const override {
    return {"t", "kinetic_energy", "min_ghost_h_over_h_ref", "wall_force_x", "wall_force_y", "steps", "rhs_evals",
            "step_levels", "block_speedup_bound"};
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
    if (parts_) return;  // distributed: no ghost series (each rank's ghosts; the particles' frames are parallel)
    ghosts_.emplace(dir_, "ghosts");  // frame k of the ghosts goes with lattice_k
    if (s.restart) ghosts_->restore(ghost_frames(s.restart->text("frames"), dir_));
  }
  bool changes_particles() const override { return parts_.has_value(); }
  std::optional<TimeLoopHooks::Resize> after_step(Real, const Real* y, const TimeLoopHooks::CarriedData& carried) override;
  std::vector<std::int64_t> global_ids() const override { return parts_ ? parts_->ids() : SceneRun::global_ids(); }
  std::vector<std::int64_t> take_share(const Checkpoint& c) override;
  LatticeRunResult result(const TimeLoopResult& loop) const;

 private:
  std::vector<Real> whole_initial_state() const {
    std::vector<Real> y(sys_.layout().with_count(Species::Gas, cfg_.particles).size(), 0.0);  // at rest
    const std::vector<Real> x0 = initial_positions(cfg_);
    std::copy(x0.begin(), x0.end(), y.begin() + static_cast<std::ptrdiff_t>(sys_.position_offset()));
    return y;
  }
  bool event(const Real* g) {
    if (g[0] <= 0) reason_ = "penetration";
    else if (g[1] <= 0) reason_ = "accumulation";
    return !reason_.empty();
  }
  void write_fields(Real t, const Real* y);  // fields_NNNN.csv (distributed: gathered on rank 0)
  // The particles' own steps on power-of-two levels (issue #17: what block steps could save at
  // most); none for a distributed run (NaN speedup) or when the evaluation fails.
  std::optional<StepLevels> own_step_levels(Real t, const Real* y) {
    if (parts_) return std::nullopt;
    std::vector<Real> dt(sys_.particles());
    if (sys_.particle_stable_dt(t, y, nullptr, dt.data()) != 0) return std::nullopt;
    return step_levels(dt);
  }

  LatticeRunConfig cfg_;
  LatticeSystem sys_;
  Communicator world_;
  std::optional<DistributedParticles<2>> parts_;  // distributed runs
  std::vector<Real> y_;                           // distributed: this rank's initial state
  MigrationSchedule schedule_;  // distributed: a migration every 20 steps, the domains anew every 100
  std::optional<ResumableVtkSeries> ghosts_;
  std::filesystem::path dir_;
  Real frame_every_ = 0, sampled_g_[2] = {1, 1};
  std::vector<Real> wrapped_;
  std::string reason_;
  double cpu0_ = 0;
};

std::vector<Real> LatticeRun::diagnostics(Real t, const Real* y, const StepperStats& st) {
  const LatticeParams& p = sys_.params();
  const int rc = sys_.prepare(y);  // density, h, ghosts of this state (distributed: collective, agreed)
  if (rc != 0 || sys_.roots(t, y, sampled_g_) != 0) sampled_g_[0] = sampled_g_[1] = 1;
  Real ke = 0;
  const Real* v = y + sys_.velocity_offset();
  for (std::size_t i = 0; i < 2 * sys_.particles(); ++i) ke += 0.5 * p.mass * v[i] * v[i];
  Vec<2> f = rc == 0 ? sys_.wall_force() : Vec<2>(NAN, NAN);
  Real min_h = rc == 0 ? sys_.min_ghost_h() : NAN;
  if (parts_) {  // every rank's: sums, and minima (the events' functions too)
    Real sums[3] = {ke, f[0], f[1]};
    world_.allreduce(sums, 3, ReduceOp::Sum);
    ke = sums[0], f = Vec<2>(sums[1], sums[2]);
    Real minima[3] = {sampled_g_[0], sampled_g_[1], min_h};
    world_.allreduce(minima, 3, ReduceOp::Min);
    sampled_g_[0] = minima[0], sampled_g_[1] = minima[1], min_h = minima[2];
  }
  const std::optional<StepLevels> levels = own_step_levels(t, y);
  return {t, ke, rc == 0 ? min_h / p.h_ref : NAN, f[0], f[1], static_cast<Real>(st.steps),
          static_cast<Real>(st.rhs_evals), levels ? static_cast<Real>(levels->count.size()) : NAN,
          levels ? levels->speedup() : NAN};
}

void LatticeRun::write_fields(Real t, const Real* y) {
  char name[64];  // fields_NNNN.csv on the frame grid, fields_end.csv at an event or a failure
  const Real k = std::round(t / frame_every_);
  if (std::abs(t - k * frame_every_) <= 1e-9 * frame_every_)
    std::snprintf(name, sizeof name, "fields_%04ld.csv", static_cast<long>(k));
  else
    std::snprintf(name, sizeof name, "fields_end.csv");
  const std::size_t n = sys_.particles();
  const Real* v = y + sys_.velocity_offset();
  if (!parts_) {
    write_file_atomically(dir_ / name, "# t=" + std::to_string(t) + "\n" +
                                           fields_csv(wrapped_.data(), v, sys_.density().data(), sys_.smoothing_length().data(), n));
    return;
  }
  std::vector<Real> local(wrapped_.begin(), wrapped_.begin() + static_cast<std::ptrdiff_t>(2 * n));  // field-major
  local.insert(local.end(), v, v + 2 * n);
  local.insert(local.end(), sys_.density().begin(), sys_.density().begin() + static_cast<std::ptrdiff_t>(n));
  local.insert(local.end(), sys_.smoothing_length().begin(), sys_.smoothing_length().begin() + static_cast<std::ptrdiff_t>(n));
  const std::vector<Real> all = gather_particles(world_, parts_->ids(), local, {2, 2, 1, 1});
  const std::size_t N = parts_->global_particles();
  world_.collectively([&] {
    if (world_.rank() == 0)
      write_file_atomically(dir_ / name, "# t=" + std::to_string(t) + "\n" +
                                             fields_csv(all.data(), all.data() + 2 * N, all.data() + 4 * N, all.data() + 5 * N, N));
  });
}

ParticleFrame LatticeRun::frame(Real t, const Real* y) {
  if (sys_.prepare_if_moved(y) != 0) throw std::runtime_error("lattice frame at t=" + std::to_string(t) + ": " + sys_.last_error());
  if (ghosts_) {
    ParticleFrame g;
    g.dim = 2;
    g.count = sys_.ghost_count();
    g.positions = sys_.all_positions().data() + 2 * sys_.particles();
    g.arrays = {{"velocity", sys_.ghosts().velocities(), 2},
                {"density", sys_.density().data() + sys_.particles(), 1},
                {"h", sys_.smoothing_length().data() + sys_.particles(), 1}};
    if (g.count > 0) ghosts_->write(g, t);
  }
  wrapped_.resize(2 * sys_.particles());
  lattice_box(sys_.params()).wrap_all(y + sys_.position_offset(), sys_.particles(), wrapped_.data());
  write_fields(t, y);
  ParticleFrame f;
  f.dim = 2;
  f.count = sys_.particles();
  f.positions = wrapped_.data();
  f.arrays = {{"velocity", y + sys_.velocity_offset(), 2},
              {"density", sys_.density().data(), 1},
              {"h", sys_.smoothing_length().data(), 1},
              {"pressure", sys_.pressure().data(), 1}};
  if (parts_) f.ids = parts_->ids().data();  // parallel VTK: each particle's global id
  return f;
}

// This rank's particles to their owners (run/migration_step.hpp); the loop continues from the new state.
std::optional<TimeLoopHooks::Resize> LatticeRun::after_step(Real, const Real* y, const TimeLoopHooks::CarriedData& carried) {
  if (!parts_) return std::nullopt;
  return migration_step(schedule_, world_, layout(), y, carried, [&](std::vector<Real>& state, std::vector<Real>* kick, bool repartition) {
    migrate_ghost_wcsph(*parts_, sys_, state, kick, repartition);
    return layout();
  });
}

std::vector<std::int64_t> LatticeRun::take_share(const Checkpoint& c) {
  if (!parts_) return SceneRun::take_share(c);
  schedule_.steps = static_cast<long>(c.scalar("steps"));  // the migration schedule continues
  const StateLayout whole = layout().with_count(Species::Gas, parts_->global_particles());
  if (c.y.size() != whole.size()) throw std::invalid_argument("--restart: the checkpoint holds another lattice");
  const std::vector<std::int64_t>& ids = parts_->take_share(c.y.data() + whole.offset(Field::Position));
  sys_.set_particles(ids);
  y_ = share_of(whole, c.y, ids);
  return ids;
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
  return std::make_unique<LatticeRun>(cfg, world());
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
  if (outcomes_.empty() || world().rank() != 0) return 0;  // distributed: rank 0 reports
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
