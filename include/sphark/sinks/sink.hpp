#pragma once
// Sink particles (Bate, Bonnell & Price 1995, MNRAS 277, 362 [BBP95]; Phantom's ptmass.F90 and
// Price et al. 2018, PASA 35, e031, sec. 2.8.4): the records, the view of the gas they read, and
// their parameters. Creation: sphark/sinks/sink_creation.hpp; accretion:
// sphark/sinks/sink_accretion.hpp; removing accreted gas from the state's arrays:
// sphark/core/compaction.hpp.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Geometry>  // cross products

#include "sphark/core/types.hpp"
#include "sphark/neighbours/periodic_box.hpp"

namespace sphark {

struct Sink {
  Vec<3> x = Vec<3>::Zero();     // position (the centre of mass of what it accreted)
  Vec<3> v = Vec<3>::Zero();     // velocity
  Real mass = 0;
  Vec<3> spin = Vec<3>::Zero();  // angular momentum about its own centre of mass, in its own frame
  Real accretion_radius = 0;     // r_acc (Phantom's h_acc)
};

// Read-only view of n gas particles (SoA, 3 values per particle for vectors). Pointers the
// caller does not need may stay null only where a function says so.
struct GasView {
  std::size_t n = 0;
  const Real* x = nullptr;      // positions
  const Real* v = nullptr;      // velocities
  const Real* mass = nullptr;   // masses
  const Real* h = nullptr;      // smoothing lengths
  const Real* rho = nullptr;    // densities
  const Real* div_v = nullptr;  // velocity divergence
  const Real* u = nullptr;      // specific THERMAL energy (for a barotropic gas:
                                // BarotropicEos::thermal_energy, not its u(rho))
  const Real* phi = nullptr;    // gravitational potential (per unit mass) of the gas at the particle

  Vec<3> position(std::size_t a) const { return Vec<3>(x[3 * a], x[3 * a + 1], x[3 * a + 2]); }
  Vec<3> velocity(std::size_t a) const { return Vec<3>(v[3 * a], v[3 * a + 1], v[3 * a + 2]); }
};

// Pair potential energy per unit mass product of two gas particles r apart with smoothing
// lengths h_a, h_b (negative; G included). Pass the gravity solver's kernel-softened form
// (Price & Monaghan 2007: phi(r, h), symmetrised (phi(r, h_a) + phi(r, h_b)) / 2, as Phantom's
// ptmass_create does). Empty: the point-mass -G / r.
using PairPotential = std::function<Real(Real r, Real h_a, Real h_b)>;

struct SinkParams {
  Real rho_sink = 0;            // creation density threshold (Phantom rho_crit)
  Real accretion_radius = 0;    // r_acc of new sinks
  Real creation_radius = 0;     // no new sink within this distance of an existing one (Phantom r_crit; 0: no limit)
  Real unconditional_fraction = 0.8;  // gas inside f r_acc is accreted without checks (Phantom f_acc)
  // A candidate denser than forced_creation_factor x rho_sink becomes a sink without the checks
  // after the first (outside_existing_sinks); 0: never (Phantom f_crit_override, "unconditional
  // sink formation if rho > f_crit_override*rho_crit"; Phantom requires it > 10 when set).
  Real forced_creation_factor = 0;
  Real G = 1;
  PairPotential pair_potential;        // see above
  std::optional<PeriodicBox<3>> box;   // minimum-image separations when set
};

// The outcome of a creation or an accretion step: the sinks after it and the gas to remove
// (sphark/core/compaction.hpp removes it from the state's fields).
struct SinkUpdate {
  std::vector<Sink> sinks;                  // all sinks after the event (a new one appended)
  std::vector<std::uint32_t> removed;       // accreted gas, ascending, unique
  std::vector<std::uint32_t> accreted_by;   // removed[k] went into sinks[accreted_by[k]]
};

}  // namespace sphark
