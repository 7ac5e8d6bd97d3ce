#include "sphark/sinks/sink_run.hpp"

#include <numeric>

#include "sphark/gravity/kernel_softening.hpp"

namespace sphark {

void SinkRunSupport::reload_log() {
  log_.creations = static_cast<long>(creations_);
  log_.accreted_particles = static_cast<long>(accreted_);
  log_.first_creation_time = first_creation_t_;
}

void SinkRunSupport::save_log() {
  created_ = log_.creations > static_cast<long>(creations_);
  creations_ = static_cast<Real>(log_.creations);
  accreted_ = static_cast<Real>(log_.accreted_particles);
  first_creation_t_ = log_.first_creation_time;
}

std::optional<TimeLoopHooks::Resize> SinkRunSupport::after_step(SpmhdScheme<3>& scheme, Real t, const Real* y) {
  reload_log();
  std::optional<TimeLoopHooks::Resize> r = sink_events(scheme, t, y, params_, log_);
  save_log();
  return r;
}

std::optional<TimeLoopHooks::Resize> SinkRunSupport::remove_active(SpmhdScheme<3>& scheme, Real t, const Real* y,
                                                                   const std::vector<std::size_t>& active) {
  reload_log();
  std::optional<TimeLoopHooks::Resize> r = events_among_active(scheme, t, y, active, params_, log_);
  save_log();
  return r;
}

void SinkRunSupport::restore_particles(SpmhdScheme<3>& scheme, const StateLayout& layout) {
  const std::size_t gas = layout.particles(Species::Gas);
  accreted_ -= static_cast<Real>(gas) - static_cast<Real>(scheme.particles());
  // equal masses: which particles does not matter; those given back start their density solves
  // from the smoothing lengths of others
  std::vector<std::size_t> kept(gas);
  for (std::size_t i = 0; i < gas; ++i) kept[i] = i % scheme.particles();
  scheme.change_particles(kept, layout.particles(Species::Sink));
}

std::vector<std::pair<std::string, Real*>> SinkRunSupport::saved_numbers() {
  return {{"sink_creations", &creations_}, {"accreted_particles", &accreted_}, {"first_sink_time", &first_creation_t_}};
}

StateLayout SinkRunSupport::restart_layout(SpmhdScheme<3>& scheme, const Checkpoint& c) {
  std::size_t gas = 0, sinks = 0;
  for (const CheckpointSpecies& s : c.species) (s.name == "sink" ? sinks : gas) = s.particles;
  std::vector<std::size_t> kept(gas);
  std::iota(kept.begin(), kept.end(), std::size_t{0});  // equal masses: which particles does not matter
  scheme.change_particles(kept, sinks);
  return scheme.layout();
}

std::vector<std::string> SinkRunSupport::columns() { return {"n_sinks", "sink_mass"}; }

std::array<Real, 2> SinkRunSupport::values(const SpmhdScheme<3>& scheme, const Real* y) {
  const std::size_t ns = scheme.sinks();
  Real mass = 0;
  if (ns > 0) {
    const Real* m = y + scheme.layout().offset(Species::Sink, Field::Mass);
    for (std::size_t k = 0; k < ns; ++k) mass += m[k];
  }
  return {static_cast<Real>(ns), mass};
}

Real angular_momentum_z(const SpmhdScheme<3>& s, const Real* y) {
  const StateLayout& L = s.layout();
  const auto x = vector_field<3>(y, L, Field::Position);
  const auto v = vector_field<3>(y, L, Field::Velocity);
  Real lz = 0;
  for (std::size_t a = 0; a < s.particles(); ++a) lz += s.masses()[a] * (x(0, a) * v(1, a) - x(1, a) * v(0, a));
  const std::size_t ns = s.sinks();
  if (ns == 0) return lz;
  const auto xs = vector_field<3>(y, L, Field::Position, Species::Sink);
  const auto vs = vector_field<3>(y, L, Field::Velocity, Species::Sink);
  const auto spin = vector_field<3>(y, L, Field::Spin, Species::Sink);
  const Real* ms = y + L.offset(Species::Sink, Field::Mass);
  for (std::size_t k = 0; k < ns; ++k) lz += ms[k] * (xs(0, k) * vs(1, k) - xs(1, k) * vs(0, k)) + spin(2, k);
  return lz;
}

PairPotential cubic_spline_pair_potential() {
  return [](Real r, Real h_a, Real h_b) {
    using KS = KernelSoftening<CubicSpline<3>>;
    return 0.5 * (KS::phi(r, h_a) + KS::phi(r, h_b));
  };
}

}  // namespace sphark
