#include "sphark/scenes/orszag_tang/orszag_tang_scene.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "sphark/diagnostics/spmhd_diagnostics.hpp"
#include "sphark/integrate/stepper.hpp"
#include "sphark/io/csv_writer.hpp"
#include "sphark/io/visualise.hpp"
#include "sphark/parallel/global_state.hpp"
#include "sphark/run/migration_step.hpp"
#include "sphark/run/restart.hpp"
#include "sphark/run/state_resort.hpp"
#include "sphark/schemes/spmhd/spmhd_migration.hpp"

namespace sphark {

namespace {

class OrszagTangRun final : public SceneRun {
 public:
  // A world with MPI: a distributed run (RCB domains, migrations on schedule_; docs/scaling.md,
  // "SPMHD and Orszag-Tang").
  OrszagTangRun(const std::string& variant, const OrszagTangParams& params, Communicator world = {})
      : ot_(variant, params), resort_{world.distributed() ? 0.0 : params.resort, 4.0 / params.nx}, world_(world) {
    if (!world_.distributed()) return;
    const StateLayout whole = ot_.scheme.layout();
    parts_.emplace(world_, ot_.y0.data() + whole.offset(Field::Position), ot_.scheme.particles(), box_);
    y_ = share_of(whole, ot_.y0, parts_->ids());
    ot_.scheme.distribute(world_, parts_->ids());
  }
  OdeSystem& system() override { return ot_.scheme; }
  const StateLayout& layout() const override { return ot_.scheme.layout(); }
  std::vector<Real> initial_state() override { return parts_ ? y_ : ot_.y0; }
  StepperOptions stepper(const CoreOptions& core, std::string_view program) override {
    StepperOptions o = SceneRun::stepper(core, program);
    o.communicator = world_;
    return o;
  }
  std::vector<std::string> columns() const override {
    return {"t", "mean_h_divB_over_B", "max_h_divB_over_B", "kinetic_energy", "magnetic_energy", "thermal_energy",
            "psi_energy", "total_energy", "momentum_x", "momentum_y", "cleaning_speed", "rhs_evals"};
  }
  std::vector<Real> diagnostics(Real t, const Real* y, const StepperStats& st) override {
    const SpmhdDiagnostics d = spmhd_diagnostics(ot_.scheme, t, y);  // (reduced over the ranks)
    return {t, d.mean_h_divb_over_b, d.max_h_divb_over_b, d.kinetic_energy, d.magnetic_energy, d.thermal_energy,
            d.psi_energy, d.total_energy, d.momentum[0], d.momentum[1], d.cleaning_speed,
            static_cast<Real>(st.rhs_evals)};
  }
  ParticleFrame frame(Real t, const Real* y) override {
    ParticleFrame f = frame_.build(ot_.scheme, t, y, &box_);
    if (parts_) f.ids = parts_->ids().data();  // parallel VTK: each particle's global id
    return f;
  }
  void settings(TimeLoopSettings& s) override { s.progress_interval = 10; }
  // the flow scrambles the particles: the state re-sorted when it pays (run/state_resort.hpp);
  // distributed: the particles migrate to their owners instead
  bool changes_particles() const override { return resort_.threshold > 0 || parts_; }
  std::optional<TimeLoopHooks::Resize> after_step(Real, const Real* y, const TimeLoopHooks::CarriedData& carried) override {
    if (!parts_) return resort_if_scrambled<2>(ot_.scheme, ot_.scheme.layout(), y, resort_, std::optional(box_));
    return migration_step(schedule_, world_, layout(), y, carried, [&](std::vector<Real>& state, std::vector<Real>* kick, bool repartition) {
      migrate_spmhd(*parts_, ot_.scheme, state, kick, repartition);
      return layout();
    });
  }
  // Distributed: checkpoints of the whole vortex; a restart on any number of ranks takes this
  // rank's RCB domain of the checkpoint's positions.
  std::vector<std::int64_t> global_ids() const override {
    return parts_ ? parts_->ids() : SceneRun::global_ids();
  }
  std::vector<std::int64_t> take_share(const Checkpoint& c) override {
    if (!parts_) return SceneRun::take_share(c);
    schedule_.steps = static_cast<long>(c.scalar("steps"));  // the migration schedule continues
    const StateLayout whole = layout().with_count(Species::Gas, parts_->global_particles());
    if (c.y.size() != whole.size()) throw std::invalid_argument("--restart: the checkpoint holds another vortex");
    const std::vector<std::int64_t>& ids = parts_->take_share(c.y.data() + whole.offset(Field::Position));
    std::vector<Real> masses(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) masses[i] = ot_.particles.m[static_cast<std::size_t>(ids[i])];
    ot_.scheme.set_particles(ids, std::move(masses));
    y_ = share_of(whole, c.y, ids);
    return ids;
  }

 private:
  OrszagTang ot_;
  StateResortOptions resort_;
  PeriodicBox<2> box_ = unit_periodic_box();
  SpmhdFrame frame_;
  Communicator world_;
  std::optional<DistributedParticles<2>> parts_;  // distributed runs
  std::vector<Real> y_;                           // distributed: this rank's initial state
  MigrationSchedule schedule_;  // distributed: a migration every 20 steps, the domains anew every 100
};

// The summary from the run's whole diagnostics table (a restarted run summarises from t = 0).
OrszagTangScene::Summary summarise(const std::string& variant, const TimeLoopResult& loop) {
  OrszagTangScene::Summary r;
  r.variant = variant;
  r.loop = loop;
  const std::string& csv = loop.diagnostics;
  const std::vector<Real> t = csv_column(csv, "t"), mean = csv_column(csv, "mean_h_divB_over_B"),
                          mx = csv_column(csv, "max_h_divB_over_B"), e = csv_column(csv, "total_energy"),
                          px = csv_column(csv, "momentum_x"), py = csv_column(csv, "momentum_y");
  if (t.empty()) return r;
  r.mean_at_end = mean.back();
  r.max_at_end = mx.back();
  for (std::size_t k = 0; k < t.size(); ++k)
    if (std::abs(t[k] - 0.5) < 1e-9) r.mean_at_half = mean[k];
  r.energy_change = (e.back() - e.front()) / e.front();
  r.momentum = std::hypot(px.back(), py.back());
  return r;
}

}  // namespace

std::string OrszagTangScene::description() const {
  return "Orszag-Tang vortex (seed 000 §IV-B, Figs. 2-3): div B control by resistivity, Euler potentials and "
         "constrained hyperbolic/parabolic cleaning";
}

void OrszagTangScene::set_defaults(CoreOptions& core) {
  core.out = "out/orszag_tang";
  core.t_end = 1;
  core.output_every = 0.05;
  core.stepper = "leapfrog";  // dt = C h / v_sig (max_stable_dt), one RHS per step
  core.rtol = 1e-4;
  core.atol = 1e-6;
}

std::vector<std::string> OrszagTangScene::stepper_names() const { return core_stepper_names(); }

void OrszagTangScene::add_options(OptionParser& p) {
  p.add("--nx", &params_.nx, "particles per row of the hexagonal lattice (rows: nearest even nx*2/sqrt(3)); paper: 512",
        Range{8, 4096});
  std::vector<std::string> allowed = orszag_tang_variants();
  allowed.push_back("all");
  p.add("--variant", &variant_, "div B control (all: the five in turn)", OneOf{allowed});
  p.add("--sigma", &params_.sigma, "cleaning damping, 1/tau = sigma c_h / h", NonNegative{});
  p.add("--alpha-b", &params_.alpha_b, "artificial resistivity strength of the resistivity variants", Positive{});
  p.add("--overclean", &params_.overclean, "cleaning speed c_h = overclean x max fast speed (cleaning variants)",
        Range{1.0, 100.0});
  p.add_flag("--local-ch", &params_.local_ch,
             "per-particle c_h = overclean x own fast speed, psi/c_h evolved (Tricco, Price & Bate 2016)");
  p.add("--courant", &params_.courant, "Courant number C of dt = C h / max(v_sig, c_h), every variant",
        Range{0.01, 1.0});
  p.add("--cleaning-courant", &params_.cleaning_courant,
        "cleaning variants: the cleaning wave's own Courant number C_h, dt = min(C h / v_sig, C_h h / (c_h + 3|v|)); "
        "0 = C (docs/spmhd.md, stability limit)",
        Range{0.0, 2.0});
  p.add("--resort", &params_.resort,
        "re-sort the state into cell order (cells of 4 spacings) when it is this far from it (0: never; 3/4: the "
        "initial lattice; speed only, docs/performance.md)",
        Range{0.0, 1.0});
}

void OrszagTangScene::check_options(const OptionParser& p, CoreOptions&, const RunControlOptions&, bool) {
  if (world().distributed() && (variant_ == "euler" || variant_ == "all"))
    p.fail("--variant", variant_ + (variant_ == "all" ? " (which includes euler)" : "") +
                            " does not run distributed: Euler potentials are serial only; pick none, resistivity, "
                            "cleaning or cleaning+resistivity");
}

std::vector<std::string> OrszagTangScene::run_names() const {
  return variant_ == "all" ? orszag_tang_variants() : std::vector<std::string>{variant_};
}

std::filesystem::path OrszagTangScene::subdirectory(const std::string& v) const {
  return v == "cleaning+resistivity" ? "cleaning_resistivity" : v;
}

void OrszagTangScene::check_restart_run(const OptionParser& p, const std::string& run) const {
  if (variant_ != "all" && variant_ != run) p.fail("--variant", variant_ + " contradicts the checkpoint (variant " + run + ")");
}

std::string OrszagTangScene::scene_text(const std::string& variant) const {
  std::string text;
  append_key_value(text, "variant", variant);
  append_key_value(text, "nx", static_cast<Real>(params_.nx));
  append_key_value(text, "sigma", params_.sigma);
  append_key_value(text, "alpha_b", params_.alpha_b);
  append_key_value(text, "overclean", params_.overclean);
  append_key_value(text, "courant", params_.courant);
  if (params_.cleaning_courant > 0) append_key_value(text, "cleaning_courant", params_.cleaning_courant);
  append_key_value(text, "local_ch", params_.local_ch ? 1.0 : 0.0);
  return text;
}

std::unique_ptr<SceneRun> OrszagTangScene::make_run(const std::string& variant, const CoreOptions&) {
  return std::make_unique<OrszagTangRun>(variant, params_, world());
}

Real OrszagTangScene::predicted_particles(const std::string&) const {
  return static_cast<Real>(params_.nx) * hexagonal_rows(params_.nx);
}

std::unique_ptr<SceneRun> OrszagTangScene::make_probe_run(const std::string& variant, const CoreOptions&,
                                                          Real particles) {
  OrszagTangParams q = params_;  // nx rows of ~2 nx / sqrt(3): nx = sqrt(N sqrt(3) / 2)
  if (predicted_particles(variant) > particles)
    q.nx = std::max(8, static_cast<int>(std::lround(std::sqrt(particles * std::sqrt(3.0) / 2))));
  return std::make_unique<OrszagTangRun>(variant, q);
}

void OrszagTangScene::finished(const std::string& variant, SceneRun&, const TimeLoopResult& result) {
  results_.push_back(summarise(variant, result));
}

int OrszagTangScene::report(const CoreOptions& core, const std::vector<std::string>& runs, bool all_ok) {
  if (results_.empty() || world().rank() != 0) return 0;  // distributed: rank 0 reports
  std::ostringstream s;
  s << "variant, nx, mean_h_divB_over_B_t0.5, mean_h_divB_over_B_end, max_h_divB_over_B_end, total_energy_change, "
       "momentum_end, steps, rhs_evals, wall_s\n";
  for (const Summary& r : results_) {
    char line[512];
    std::snprintf(line, sizeof line, "%s, %d, %.4e, %.4e, %.4e, %.3e, %.3e, %ld, %ld, %.1f%s\n", r.variant.c_str(),
                  params_.nx, r.mean_at_half, r.mean_at_end, r.max_at_end, r.energy_change, r.momentum,
                  r.loop.stats.steps, r.loop.stats.rhs_evals, r.loop.wall_seconds, r.loop.ok() ? "" : " (FAILED)");
    s << line;
  }
  std::cout << s.str();
  const bool all = runs.size() == orszag_tang_variants().size();
  const std::string name = all ? "summary.csv" : "summary_" + subdirectory(results_.front().variant).string() + ".csv";
  write_file_atomically(core.out / name, s.str());
  if (all_ok && core.render) run_python("orszag_tang.py", {"--dir", core.out.string()}, false);
  return 0;
}

// per variant: div B beside the magnetic pressure
std::vector<Scene::ParaViewStateFile> OrszagTangScene::paraview_states(const std::vector<std::string>& runs) const {
  std::vector<ParaViewStateFile> states;
  for (const std::string& v : runs)
    states.push_back({subdirectory(v) / "view.pvsm", {{"orszag_tang.pvd", "div_B"}, {"orszag_tang.pvd", "magnetic_pressure"}}});
  return states;
}

}  // namespace sphark
