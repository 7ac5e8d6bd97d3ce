#include "sphark/sinks/sink_creation.hpp"

#include <stdexcept>
#include <utility>

#include "sphark/sinks/sink_accretion.hpp"

namespace sphark {

namespace {
Vec<3> separation(const Vec<3>& a, const Vec<3>& b, const std::optional<PeriodicBox<3>>& box) {
  const Vec<3> d = a - b;
  return box ? box->minimum_image(d) : d;
}

void require(const void* p, const char* what) {
  if (!p) throw std::invalid_argument(std::string("sink creation: the gas view needs ") + what);
}
}  // namespace

std::string to_string(SinkCheck c) {
  switch (c) {
    case SinkCheck::ok: return "ok";
    case SinkCheck::no_candidate: return "no gas above rho_sink";
    case SinkCheck::inside_existing_sink: return "within the creation radius of a sink";
    case SinkCheck::diverging_flow: return "div v >= 0";
    case SinkCheck::smoothing_length_too_large: return "2 h >= r_acc";
    case SinkCheck::not_potential_minimum: return "not at the potential minimum";
    case SinkCheck::too_hot: return "alpha > 1/2";
    case SinkCheck::too_hot_and_rotating: return "alpha + beta > 1";
    case SinkCheck::unbound: return "E_tot >= 0";
  }
  return "unknown";
}

std::optional<std::size_t> densest_gas_particle(const GasView& gas, Real rho_sink) {
  require(gas.rho, "rho");
  std::optional<std::size_t> best;
  for (std::size_t a = 0; a < gas.n; ++a)
    if (gas.rho[a] > rho_sink && (!best || gas.rho[a] > gas.rho[*best])) best = a;
  return best;
}

std::vector<std::uint32_t> clump_members(const GasView& gas, std::size_t candidate, Real radius,
                                         const std::optional<PeriodicBox<3>>& box) {
  require(gas.x, "x");
  const Vec<3> xi = gas.position(candidate);
  std::vector<std::uint32_t> out;
  for (std::size_t a = 0; a < gas.n; ++a)
    if (a == candidate || separation(gas.position(a), xi, box).squaredNorm() < radius * radius)
      out.push_back(static_cast<std::uint32_t>(a));
  return out;
}

ClumpEnergies clump_energies(const GasView& gas, const std::vector<std::uint32_t>& clump, const SinkParams& params) {
  require(gas.x, "x"), require(gas.v, "v"), require(gas.mass, "mass"), require(gas.h, "h"), require(gas.u, "u");
  ClumpEnergies e;
  if (clump.empty()) return e;
  // centre of mass and its velocity, relative to the first member (periodic-safe)
  const Vec<3> x0 = gas.position(clump[0]);
  Real M = 0;
  Vec<3> mx = Vec<3>::Zero(), mv = Vec<3>::Zero();
  for (std::uint32_t a : clump) {
    M += gas.mass[a];
    mx += gas.mass[a] * separation(gas.position(a), x0, params.box);
    mv += gas.mass[a] * gas.velocity(a);
  }
  const Vec<3> xc = x0 + mx / M, vc = mv / M;
  Vec<3> per_axis = Vec<3>::Zero();
  for (std::uint32_t a : clump) {
    const Real m = gas.mass[a];
    const Vec<3> r = separation(gas.position(a), xc, params.box), w = gas.velocity(a) - vc;
    e.kinetic += 0.5 * m * w.squaredNorm();
    e.thermal += m * gas.u[a];
    const Vec<3> L = r.cross(w);
    for (int k = 0; k < 3; ++k) {
      const Real perp2 = r.squaredNorm() - r[k] * r[k];  // distance^2 from the axis k through xc
      if (perp2 > 0) per_axis[k] += 0.5 * m * L[k] * L[k] / perp2;
    }
  }
  e.rotational = per_axis.norm();
  for (std::size_t j = 0; j < clump.size(); ++j)
    for (std::size_t k = j + 1; k < clump.size(); ++k) {
      const std::uint32_t a = clump[j], b = clump[k];
      const Real r = separation(gas.position(a), gas.position(b), params.box).norm();
      const Real phi = params.pair_potential ? params.pair_potential(r, gas.h[a], gas.h[b]) : -params.G / r;
      e.potential += gas.mass[a] * gas.mass[b] * phi;
    }
  return e;
}

SinkCheck check_outside_existing_sinks(const GasView& gas, std::size_t candidate, const std::vector<Sink>& sinks,
                                       const SinkParams& params) {
  require(gas.x, "x");
  for (const Sink& s : sinks)
    if (separation(gas.position(candidate), s.x, params.box).norm() < params.creation_radius)
      return SinkCheck::inside_existing_sink;
  return SinkCheck::ok;
}

SinkCheck check_converging_flow(const GasView& gas, std::size_t candidate) {
  require(gas.div_v, "div_v");
  return gas.div_v[candidate] < 0 ? SinkCheck::ok : SinkCheck::diverging_flow;
}

SinkCheck check_smoothing_length(const GasView& gas, std::size_t candidate, Real r_acc) {
  require(gas.h, "h");
  return 2 * gas.h[candidate] < r_acc ? SinkCheck::ok : SinkCheck::smoothing_length_too_large;
}

SinkCheck check_potential_minimum(const GasView& gas, std::size_t candidate, const std::vector<std::uint32_t>& clump) {
  require(gas.phi, "phi");
  // ties within round-off count as the minimum (on a symmetric configuration several particles
  // share it, and which one the summation order puts lowest is not physics)
  const Real floor = gas.phi[candidate] - 1e-12 * std::abs(gas.phi[candidate]);
  for (std::uint32_t a : clump)
    if (gas.phi[a] < floor) return SinkCheck::not_potential_minimum;
  return SinkCheck::ok;
}

SinkCheck check_thermal(const ClumpEnergies& e) { return e.alpha() <= 0.5 ? SinkCheck::ok : SinkCheck::too_hot; }

SinkCheck check_thermal_and_rotation(const ClumpEnergies& e) {
  return e.alpha() + e.beta() <= 1 ? SinkCheck::ok : SinkCheck::too_hot_and_rotating;
}

SinkCheck check_bound(const ClumpEnergies& e) { return e.total() < 0 ? SinkCheck::ok : SinkCheck::unbound; }

SinkCreationTest test_sink_creation(const GasView& gas, const std::vector<Sink>& sinks, const SinkParams& params) {
  if (!(params.accretion_radius > 0)) throw std::invalid_argument("sink creation: r_acc must be positive");
  if (!(params.forced_creation_factor == 0 || params.forced_creation_factor > 1))
    throw std::invalid_argument("sink creation: forced_creation_factor must be 0 (never) or > 1");
  SinkCreationTest t;
  const std::optional<std::size_t> c = densest_gas_particle(gas, params.rho_sink);
  if (!c) return t;
  t.candidate = *c;
  t.result = check_outside_existing_sinks(gas, *c, sinks, params);
  if (t.result == SinkCheck::ok && params.forced_creation_factor > 0 &&
      gas.rho[*c] > params.forced_creation_factor * params.rho_sink) {
    t.forced = true;
    t.clump = clump_members(gas, *c, params.accretion_radius, params.box);
    return t;
  }
  if (t.result == SinkCheck::ok) t.result = check_converging_flow(gas, *c);
  if (t.result == SinkCheck::ok) t.result = check_smoothing_length(gas, *c, params.accretion_radius);
  if (t.result != SinkCheck::ok) return t;
  t.clump = clump_members(gas, *c, params.accretion_radius, params.box);
  t.result = check_potential_minimum(gas, *c, t.clump);
  if (t.result != SinkCheck::ok) return t;
  t.energies = clump_energies(gas, t.clump, params);
  t.result = check_thermal(t.energies);
  if (t.result == SinkCheck::ok) t.result = check_thermal_and_rotation(t.energies);
  if (t.result == SinkCheck::ok) t.result = check_bound(t.energies);
  return t;
}

Sink sink_from_clump(const GasView& gas, const std::vector<std::uint32_t>& clump, Real r_acc,
                     const std::optional<PeriodicBox<3>>& box) {
  if (clump.empty()) throw std::invalid_argument("sink_from_clump: empty clump");
  Sink seed;  // massless, at rest, at the first member: absorbing the clump makes it the clump
  seed.x = gas.position(clump[0]);
  seed.accretion_radius = r_acc;
  return absorb(seed, gas, clump, box);
}

SinkUpdate sink_made_of(const GasView& gas, const std::vector<Sink>& sinks, const std::vector<std::uint32_t>& clump,
                        const SinkParams& params) {
  SinkUpdate up;
  up.sinks = sinks;
  up.sinks.push_back(sink_from_clump(gas, clump, params.accretion_radius, params.box));
  up.removed = clump;
  up.accreted_by.assign(clump.size(), static_cast<std::uint32_t>(sinks.size()));
  return up;
}

SinkUpdate create_sink_if_allowed(const GasView& gas, const std::vector<Sink>& sinks, const SinkParams& params,
                                  SinkCreationTest* test) {
  SinkCreationTest t = test_sink_creation(gas, sinks, params);
  SinkUpdate up = t.result == SinkCheck::ok ? sink_made_of(gas, sinks, t.clump, params) : SinkUpdate{sinks, {}, {}};
  if (test) *test = std::move(t);
  return up;
}

}  // namespace sphark
