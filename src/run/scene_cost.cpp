#include "scene_cost.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>

namespace sphark {

Real Scene::predicted_particles(const std::string&) const { return std::numeric_limits<Real>::quiet_NaN(); }

namespace detail {
namespace {

ProbeSubject probe_subject(std::unique_ptr<SceneRun> run, const CoreOptions& core) {
  ProbeSubject s;
  s.system = &run->system();
  s.y0 = run->initial_state();
  s.stepper = run->stepper(core, "");  // "": quiet
  s.particles = static_cast<double>(run->layout().particles());
  SceneRun* r = run.get();
  s.diagnostics = [r](Real t, const Real* y) { r->diagnostics(t, y, StepperStats{}); };
  s.owner = std::shared_ptr<SceneRun>(std::move(run));
  return s;
}

}  // namespace

PlannedCost plan_cost(Scene& scene, const std::string& run, const CoreOptions& core, const OptionParser& p) {
  PlannedCost c;
  const Real n = scene.predicted_particles(run);
  if (std::isnan(n)) return c;
  try {
    std::unique_ptr<SceneRun> probe = scene.make_probe_run(run, core, std::min<Real>(n, kProbeParticles));
    if (!probe) return c;
    c.probe = measure_probe([&] { return probe_subject(std::move(probe), core); }, core.t_end);
  } catch (const std::invalid_argument& e) {
    p.fail(scene.size_option(), e.what());
  } catch (const std::exception&) {
    return c;  // no estimate; the run itself reports what went wrong
  }
  c.known = true;
  c.memory = estimate_memory(n, c.probe);
  if (!c.memory.fits()) p.fail(scene.size_option(), memory_refusal(c.memory));
  return c;
}

std::string first_line(const std::string& program, const std::string& run, const PlannedCost& cost, SceneRun& built,
                       const StepperOptions& so, Real t0, const Real* y0, Real t_end, Real longest_step) {
  CostEstimate e = cost.memory;
  e.particles = static_cast<double>(built.layout().particles());
  e.bytes = e.particles * e.bytes_per_particle;
  estimate_time(e, built.system(), so, t0, y0, t_end, longest_step, cost.probe);
  if (built.stable_step_falls()) e.steps_at_least = true;
  return cost_line(program, run, e);
}

}  // namespace detail
}  // namespace sphark
