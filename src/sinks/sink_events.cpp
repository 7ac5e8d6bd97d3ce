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

// ... from the scheme's last evaluation (its densities, h, div v, potential) and y's positions
// and velocities.
GasArrays gas_as_evaluated(const SpmhdScheme<3>& s, const Real* y) {
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

GasArrays gas_of(SpmhdScheme<3>& s, Real t, const Real* y) {
  if (s.evaluate(t, y) != 0) throw std::runtime_error("sink events at t=" + std::to_string(t) + ": " + s.last_error());
  return gas_as_evaluated(s, y);
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

// The gas particles an event keeps (ascending).
std::vector<std::size_t> kept_gas(const SpmhdScheme<3>& s, const SinkUpdate& update) {
  const std::vector<std::uint32_t> survivors = surviving_indices(s.particles(), update.removed);
  return {survivors.begin(), survivors.end()};
}

// The state after the event: the gas without `removed`, the sinks `sinks` (all of them rewritten).
TimeLoopHooks::Resize apply(SpmhdScheme<3>& s, const Real* y, const SinkUpdate& update) {
  const StateLayout& from = s.layout();
  const std::vector<std::size_t> kept = kept_gas(s, update);
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

bool sink_creation_due(const SpmhdScheme<3>& s, const SinkParams& params) {
  const std::vector<Real>& rho = s.rho();
  return !rho.empty() && *std::max_element(rho.begin(), rho.end()) > params.rho_sink;
}


namespace {

// Where each entry of the state after an event that kept the gas `kept` and has `sinks` sinks
// (the old ones in place, new ones after them) came from; kNoEntrySource for a new sink's.
std::vector<std::size_t> entry_sources_after(const StateLayout& from, const std::vector<std::size_t>& kept,
                                             std::size_t sinks) {
  const StateLayout fewer_gas = from.with_count(Species::Gas, kept.size());
  const std::vector<std::size_t> gas = entry_sources(from, fewer_gas, Species::Gas, kept);
  std::vector<std::size_t> same(std::min(from.particles(Species::Sink), sinks));
  std::iota(same.begin(), same.end(), std::size_t{0});
  std::vector<std::size_t> out =
      entry_sources(fewer_gas, fewer_gas.with_count(Species::Sink, sinks), Species::Sink, same);
  for (std::size_t& e : out)
    if (e != kNoEntrySource) e = gas[e];
  return out;
}

// The event `update` made inside a step: the new state with its entries' sources.
TimeLoopHooks::Resize apply_with_sources(SpmhdScheme<3>& s, const Real* y, const SinkUpdate& update) {
  const StateLayout from = s.layout();
  const std::vector<std::size_t> kept = kept_gas(s, update);
  TimeLoopHooks::Resize r = apply(s, y, update);
  r.entry_source = entry_sources_after(from, kept, update.sinks.size());
  return r;
}

// Accretion of the active gas alone (see accrete_active).
std::optional<SinkUpdate> accretion_among(const SpmhdScheme<3>& s, const Real* y, const std::vector<std::size_t>& active,
                                          const std::vector<Sink>& sinks, const SinkParams& params) {
  const GasView all = moving_gas(s, y);
  std::vector<std::size_t> gas;  // the active gas, as particles of the view below
  for (std::size_t i : active)
    if (i < all.n) gas.push_back(i);
  if (gas.empty()) return std::nullopt;
  std::vector<Real> x(3 * gas.size()), v(3 * gas.size()), m(gas.size());
  for (std::size_t j = 0; j < gas.size(); ++j) {
    std::copy_n(all.x + 3 * gas[j], 3, x.begin() + 3 * j);
    std::copy_n(all.v + 3 * gas[j], 3, v.begin() + 3 * j);
    m[j] = all.mass[gas[j]];
  }
  GasView view;
  view.n = gas.size(), view.x = x.data(), view.v = v.data(), view.mass = m.data();
  SinkUpdate fed = accrete(view, sinks, params);
  if (fed.removed.empty() || fed.removed.size() >= s.particles()) return std::nullopt;
  for (std::uint32_t& r : fed.removed) r = static_cast<std::uint32_t>(gas[r]);  // ascending still
  return fed;
}

// Creation from active gas alone (see accrete_active): the candidate and its whole clump active.
std::optional<SinkUpdate> creation_among(const SpmhdScheme<3>& s, const Real* y, const std::vector<std::size_t>& active,
                                         const std::vector<Sink>& sinks, const SinkParams& params, SinkEventLog& log) {
  if (!sink_creation_due(s, params)) return std::nullopt;
  const GasArrays gas = gas_as_evaluated(s, y);
  const SinkCreationTest test = test_sink_creation(gas.view, sinks, params);
  const auto is_active = [&](std::size_t i) { return std::binary_search(active.begin(), active.end(), i); };
  if (test.result == SinkCheck::no_candidate || !is_active(test.candidate)) return std::nullopt;
  for (std::uint32_t j : test.clump)
    if (!is_active(j)) return std::nullopt;  // Phantom's check 3: every particle within r_acc active
  if (test.result != SinkCheck::ok) {
    ++log.refusals[test.result];
    return std::nullopt;
  }
  if (test.clump.size() >= s.particles()) return std::nullopt;  // (sink_events decides)
  if (test.forced) ++log.forced_creations;
  return sink_made_of(gas.view, sinks, test.clump, params);
}

}  // namespace

std::optional<TimeLoopHooks::Resize> events_among_active(SpmhdScheme<3>& s, Real t, const Real* y,
                                                         const std::vector<std::size_t>& active,
                                                         const SinkParams& params, SinkEventLog& log) {
  const std::vector<Sink> sinks = sinks_of(s, y, params.accretion_radius);
  if (!sinks.empty()) {
    if (const std::optional<SinkUpdate> fed = accretion_among(s, y, active, sinks, params)) {
      log.accreted_particles += static_cast<long>(fed->removed.size());
      return apply_with_sources(s, y, *fed);
    }
  }
  const std::optional<SinkUpdate> made = creation_among(s, y, active, sinks, params, log);
  if (!made) return std::nullopt;
  ++log.creations;
  if (log.first_creation_time < 0) log.first_creation_time = t;
  return apply_with_sources(s, y, *made);
}

std::vector<std::size_t> creation_clump_to_wake(const SpmhdScheme<3>& s, const Real* y,
                                                const std::vector<std::size_t>& active, const SinkParams& params) {
  if (!sink_creation_due(s, params)) return {};
  GasView view = moving_gas(s, y);
  view.rho = s.rho().data();
  const std::optional<std::size_t> candidate = densest_gas_particle(view, params.rho_sink);
  if (!candidate) return {};
  if (check_outside_existing_sinks(view, *candidate, sinks_of(s, y, params.accretion_radius), params) != SinkCheck::ok)
    return {};
  std::vector<std::size_t> wake;
  for (std::uint32_t j : clump_members(view, *candidate, params.accretion_radius, params.box))
    if (!std::binary_search(active.begin(), active.end(), std::size_t{j})) wake.push_back(j);
  return wake;
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
      return apply_with_sources(s, y, fed);
    }
  }
  // Creation needs the densities at y: evaluated only when the last evaluation's densest particle
  // came within a factor 10 of rho_sink (a step changes the density by a few per cent at most),
  // and not again when the last RHS evaluated every particle at y's positions (a leapfrog's step
  // ends so; its div v is then of the predicted velocities, as at the block steps' events).
  if (s.rho().empty() || *std::max_element(s.rho().begin(), s.rho().end()) < 0.1 * params.rho_sink) return std::nullopt;
  const GasArrays gas = s.fully_evaluated_at_positions_of(y) ? gas_as_evaluated(s, y) : gas_of(s, t, y);
  SinkCreationTest test;
  const SinkUpdate created = create_sink_if_allowed(gas.view, sinks, params, &test);
  if (created.removed.empty()) {
    if (test.result != SinkCheck::no_candidate) ++log.refusals[test.result];
    return std::nullopt;
  }
  if (created.removed.size() >= s.particles()) {
    log.gas_exhausted = true;
    return std::nullopt;
  }
  ++log.creations;
  if (test.forced) ++log.forced_creations;
  if (log.first_creation_time < 0) log.first_creation_time = t;
  return apply_with_sources(s, y, created);
}

}  // namespace sphark
