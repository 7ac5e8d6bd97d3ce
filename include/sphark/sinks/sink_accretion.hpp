#pragma once
// Accretion onto sinks (BBP95 sec. 2.2.3; Phantom ptmass_check_acc / ptmass_accrete /
// update_ptmass). A gas particle a, r = |x_a - x_s| from sink s:
//   r < f r_acc,s                 accreted unconditionally (f = 0.8; by the nearest such sink)
//   f r_acc,s <= r < r_acc,s      accreted by s only if, with w = v_a - v_s,
//       bound:        e = |w|^2 / 2 - G M_s / r < 0
//       most bound:   e is the smallest among the sinks that have a within their r_acc
//       low spin:     |r x w|^2 < G M_s r_acc,s (below a circular orbit at r_acc)
// Every decision uses the sinks' states before this accretion step (the order of the gas does
// not matter). Each sink s then absorbs its gas A_s (sums in ascending particle order):
//   M' = M + sum m,  x' = x + sum m (x_a - x) / M',  v' = v + sum m (v_a - v) / M',
//   S' = S + sum m (x_a - x) x (v_a - v) - M' (x' - x) x (v' - v),
// which keeps mass, momentum and angular momentum (sum m x x v + M x x v + S) to round-off.
#include <cstdint>
#include <vector>

#include "sphark/sinks/sink.hpp"

namespace sphark {

// Which sink takes gas particle a (index into sinks), or -1. Needs gas.x, v.
long accreting_sink(const GasView& gas, std::size_t a, const std::vector<Sink>& sinks, const SinkParams& params);

// s absorbs the gas particles `taken` (any order; summed ascending).
Sink absorb(const Sink& s, const GasView& gas, const std::vector<std::uint32_t>& taken,
            const std::optional<PeriodicBox<3>>& box);

// One accretion step over all gas. Needs gas.x, v, mass.
SinkUpdate accrete(const GasView& gas, const std::vector<Sink>& sinks, const SinkParams& params);

}  // namespace sphark
