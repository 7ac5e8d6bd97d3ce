#pragma once
// Re-sorting a run's state into spatial order (issue #19): the pair loops visit particles in
// cell order, and gathering a state in another order (and scattering the derivatives back) goes
// through memory out of sequence; the rows also sum in particle order. After every step the
// gas's positions say how far the state is from cell order (scrambled_fraction, cells of side
// `cell`: one O(N) pass); above `threshold` the gas is renumbered in cell order (cell_order),
// the scheme follows (change_particles with the permutation) and the stepper continues with its
// carried data moved along (TimeLoopHooks::Resize::entry_source). A function of (t, y) alone: a
// restarted run re-sorts at the same steps, into the same order. Particle numbers in the outputs
// change at each re-sort (a lattice's initial order included).
#include <cstddef>
#include <numeric>
#include <optional>
#include <vector>

#include "sphark/neighbours/spatial_order.hpp"
#include "sphark/run/time_loop.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark {

struct StateResortOptions {
  Real threshold = 0;  // re-sort above this scrambled fraction; 0: never
  Real cell = 0;       // side of the cells (e.g. the neighbour search's, a few mean spacings)
};

// The new layout, state and entry map when the state is to be re-sorted (the scheme already
// renumbered), nothing otherwise. atol: per-entry tolerances of the run, moved along (or null).
template <int D, class Scheme>
std::optional<TimeLoopHooks::Resize> resort_if_scrambled(Scheme& scheme, const StateLayout& layout, const Real* y,
                                                         const StateResortOptions& o, const std::optional<PeriodicBox<D>>& box,
                                                         const std::vector<Real>* atol = nullptr) {
  if (!(o.threshold > 0)) return std::nullopt;
  const std::size_t n = layout.particles(Species::Gas);
  const Real* x = y + layout.offset(Species::Gas, Field::Position);
  if (scrambled_fraction<D>(x, n, o.cell, box) <= o.threshold) return std::nullopt;
  const std::vector<std::size_t> order = cell_order<D>(x, n, o.cell, box);
  TimeLoopHooks::Resize r;
  r.layout = layout;
  r.y = resize_species(layout, y, layout, Species::Gas, order);
  std::vector<Real> entries(layout.size());  // entry k holds k: exact in a double below 2^53
  std::iota(entries.begin(), entries.end(), Real(0));
  const std::vector<Real> source = resize_species(layout, entries.data(), layout, Species::Gas, order);
  r.entry_source.assign(source.begin(), source.end());
  if (atol && atol->size() == layout.size()) r.atol = resize_species(layout, atol->data(), layout, Species::Gas, order);
  scheme.change_particles(order, scheme.sinks());
  return r;
}

}  // namespace sphark
