#include "sphark/sinks/sink_events.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "sphark/core/compaction.hpp"
#include "sphark/sinks/sink_accretion.hpp"

namespace sphark {

namespace {

// The gas of state y as the sink functions read it (particle order), with the arrays it points into.
struct GasArrays {
  std::vector<Real> thermal;
  GasView view;
};

GasArrays gas_of(SpmhdScheme<3>& s, Real t, const Real* y) {
  if (s.evaluate(t, y) != 0) throw std::runtime_error("sink events at t=" + std::to_string(t) + ": " + s.last_error());
  const StateLayout& L = s.layout();
  GasArrays g;
  const std::size_t n = s.particles();
  g.thermal.resize(n);
  const BarotropicEos* eos = s.barotropic_eos();
  for (std::size_t a = 0; a < n; ++a)
    g.thermal[a] = eos ? eos->thermal_energy(s.rho()[a]) : y[L.offset(Field::InternalEnergy) + a];
  g.view = {n, y + L.offset(Field::Position), y + L.offset(Field::Velocity), s.masses().data(), s.h().data(),
            s.rho().data(), s.div_v().data(), g.thermal.data(), s.potential().data()};
  return g;
}

// The gas of state y as accretion reads it: positions, velocities, masses.
GasView moving_gas(const SpmhdScheme<3>& s, const Real* y) {
  const StateLayout& L = s.layout();
  GasView moving;
  moving.n = s.particles();
  moving.x = y + L.offset(Field::Position);
  moving.v = y + L.offset(Field::Velocity);
  moving.mass = s.masses().data();
  return moving;
}

// The state after the event: the gas without `removed`, the sinks `sinks` (all of them rewritten).
TimeLoopHooks::Resize apply(SpmhdScheme<3>& s, const Real* y, const SinkUpdate& update) {
  const StateLayout& from = s.layout();
  const std::vector<std::uint32_t> survivors = surviving_indices(s.particles(), update.removed);
  const std::vector<std::size_t> kept(survivors.begin(), survivors.end());
  const StateLayout fewer_gas = from.with_count(Species::Gas, kept.size());
  const std::vector<Real> y_gas = resize_species(from, y, fewer_gas, Species::Gas, kept);
  const std::size_t old_sinks = from.particles(Species::Sink), new_sinks = update.sinks.size();
  std::vector<std::size_t> same(std::min(old_sinks, new_sinks));
  std::iota(same.begin(), same.end(), std::size_t{0});
  const StateLayout to = fewer_gas.with_count(Species::Sink, new_sinks);
  std::vector<Real> y_new = resize_species(fewer_gas, y_gas.data(), to, Species::Sink, same);
  for (std::size_t k = 0; k < new_sinks; ++k) {
    const Sink& sk = update.sinks[k];
    Eigen::Map<Vec<3>>(y_new.data() + to.offset(Species::Sink, Field::Position) + 3 * k) = sk.x;
    Eigen::Map<Vec<3>>(y_new.data() + to.offset(Species::Sink, Field::Velocity) + 3 * k) = sk.v;
    y_new[to.offset(Species::Sink, Field::Mass) + k] = sk.mass;
    Eigen::Map<Vec<3>>(y_new.data() + to.offset(Species::Sink, Field::Spin) + 3 * k) = sk.spin;
  }
  s.change_particles(kept, new_sinks);
  return {to, std::move(y_new), {}, {}, {}};
}

}  // namespace

std::vector<Sink> sinks_of(const SpmhdScheme<3>& s, const Real* y, Real accretion_radius) {
  const StateLayout& L = s.layout();
  std::vector<Sink> sinks(s.sinks());
  for (std::size_t k = 0; k < sinks.size(); ++k) {
    sinks[k].x = Eigen::Map<const Vec<3>>(y + L.offset(Species::Sink, Field::Position) + 3 * k);
    sinks[k].v = Eigen::Map<const Vec<3>>(y + L.offset(Species::Sink, Field::Velocity) + 3 * k);
    sinks[k].mass = y[L.offset(Species::Sink, Field::Mass) + k];
    sinks[k].spin = Eigen::Map<const Vec<3>>(y + L.offset(Species::Sink, Field::Spin) + 3 * k);
    sinks[k].accretion_radius = accretion_radius;
  }
  return sinks;
}

bool sink_event_due(const SpmhdScheme<3>& s, const Real* y, const SinkParams& params) {
  const std::vector<Real>& rho = s.rho();
  if (!rho.empty() && *std::max_element(rho.begin(), rho.end()) > params.rho_sink) return true;
  const std::vector<Sink> sinks = sinks_of(s, y, params.accretion_radius);
  return !sinks.empty() && !accrete(moving_gas(s, y), sinks, params).removed.empty();
}

std::optional<TimeLoopHooks::Resize> sink_events(SpmhdScheme<3>& s, Real t, const Real* y, const SinkParams& params,
                                                 SinkEventLog& log) {
  const std::vector<Sink> sinks = sinks_of(s, y, params.accretion_radius);
  if (!sinks.empty()) {  // accretion reads positions, velocities and masses only: no evaluation
    const SinkUpdate fed = accrete(moving_gas(s, y), sinks, params);
    if (fed.removed.size() >= s.particles()) {
      log.gas_exhausted = true;
      return std::nullopt;
    }
    if (!fed.removed.empty()) {
      log.accreted_particles += static_cast<long>(fed.removed.size());
      return apply(s, y, fed);
    }
  }
  // Creation needs the densities at y: evaluated only when the last evaluation's densest particle
  // came within a factor 10 of rho_sink (a step changes the density by a few per cent at most).
  if (s.rho().empty() || *std::max_element(s.rho().begin(), s.rho().end()) < 0.1 * params.rho_sink) return std::nullopt;
  const GasArrays gas = gas_of(s, t, y);
  SinkCheck why = SinkCheck::ok;
  const SinkUpdate created = create_sink_if_allowed(gas.view, sinks, params, &why);
  if (created.removed.empty()) {
    if (why != SinkCheck::no_candidate) ++log.refusals[why];
    return std::nullopt;
  }
  if (created.removed.size() >= s.particles()) {
    log.gas_exhausted = true;
    return std::nullopt;
  }
  ++log.creations;
  if (log.first_creation_time < 0) log.first_creation_time = t;
  return apply(s, y, created);
}

}  // namespace sphark
