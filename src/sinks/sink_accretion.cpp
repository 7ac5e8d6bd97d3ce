#include "sphark/sinks/sink_accretion.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>


namespace sphark {

namespace {
Vec<3> separation(const Vec<3>& a, const Vec<3>& b, const std::optional<PeriodicBox<3>>& box) {
  const Vec<3> d = a - b;
  return box ? box->minimum_image(d) : d;
}
}  // namespace

long accreting_sink(const GasView& gas, std::size_t a, const std::vector<Sink>& sinks, const SinkParams& params) {
  const Vec<3> xa = gas.position(a), va = gas.velocity(a);
  long nearest_inner = -1, most_bound = -1;
  Real nearest_r2 = std::numeric_limits<Real>::infinity(), lowest_e = 0;
  for (std::size_t s = 0; s < sinks.size(); ++s) {
    const Sink& k = sinks[s];
    const Vec<3> r = separation(xa, k.x, params.box);
    const Real r2 = r.squaredNorm(), racc = k.accretion_radius, f = params.unconditional_fraction;
    if (r2 >= racc * racc) continue;
    if (r2 < f * f * racc * racc) {  // inside f r_acc: no checks
      if (r2 < nearest_r2) nearest_r2 = r2, nearest_inner = static_cast<long>(s);
      continue;
    }
    const Vec<3> w = va - k.v;
    const Real e = 0.5 * w.squaredNorm() - params.G * k.mass / std::sqrt(r2);  // specific orbital energy
    if (e < lowest_e) lowest_e = e, most_bound = static_cast<long>(s);
  }
  if (nearest_inner >= 0) return nearest_inner;
  if (most_bound < 0) return -1;  // bound to no sink
  const Sink& k = sinks[most_bound];
  const Vec<3> r = separation(xa, k.x, params.box), w = va - k.v;
  const Real j2 = r.cross(w).squaredNorm();  // specific angular momentum squared
  return j2 < params.G * k.mass * k.accretion_radius ? most_bound : -1;  // below circular at r_acc
}

Sink absorb(const Sink& s, const GasView& gas, const std::vector<std::uint32_t>& taken,
            const std::optional<PeriodicBox<3>>& box) {
  std::vector<std::uint32_t> order(taken);
  std::sort(order.begin(), order.end());
  Real dm = 0;
  Vec<3> m_dx = Vec<3>::Zero(), m_dv = Vec<3>::Zero(), dL = Vec<3>::Zero();
  for (std::uint32_t a : order) {  // relative to the sink's old state
    const Real m = gas.mass[a];
    const Vec<3> dx = separation(gas.position(a), s.x, box), dv = gas.velocity(a) - s.v;
    dm += m;
    m_dx += m * dx;
    m_dv += m * dv;
    dL += m * dx.cross(dv);
  }
  Sink out = s;
  out.mass = s.mass + dm;
  if (!(out.mass > 0)) throw std::invalid_argument("absorb: a sink needs positive mass");
  const Vec<3> shift = m_dx / out.mass, kick = m_dv / out.mass;
  out.x = s.x + shift;
  if (box) out.x = box->wrap(out.x);
  out.v = s.v + kick;
  out.spin = s.spin + dL - out.mass * shift.cross(kick);
  return out;
}

SinkUpdate accrete(const GasView& gas, const std::vector<Sink>& sinks, const SinkParams& params) {
  if (!gas.x || !gas.v || !gas.mass) throw std::invalid_argument("accrete: the gas view needs x, v and mass");
  SinkUpdate up;
  std::vector<std::vector<std::uint32_t>> taken(sinks.size());
  for (std::size_t a = 0; a < gas.n; ++a) {
    const long s = accreting_sink(gas, a, sinks, params);
    if (s < 0) continue;
    up.removed.push_back(static_cast<std::uint32_t>(a));
    up.accreted_by.push_back(static_cast<std::uint32_t>(s));
    taken[s].push_back(static_cast<std::uint32_t>(a));
  }
  up.sinks = sinks;
  for (std::size_t s = 0; s < sinks.size(); ++s)
    if (!taken[s].empty()) up.sinks[s] = absorb(sinks[s], gas, taken[s], params.box);
  return up;
}

}  // namespace sphark
