#pragma once
// Sink creation (BBP95 sec. 2.2.2; Phantom ptmass_create). The densest gas particle above
// rho_sink is the candidate; its clump is the candidate and every gas particle within r_acc of
// it. A sink is created only if every check passes; each check is its own function and returns
// its own reason:
//   outside_existing_sinks  |x_i - x_s| >= creation radius for every sink s
//   converging_flow         div v_i < 0
//   small_smoothing_length  2 h_i < r_acc
//   potential_minimum       phi_i <= phi_j for every j of the clump
//   thermal                 alpha = |E_th / E_pot| <= 1/2                 (BBP95 eq. 2.9)
//   thermal_and_rotation    alpha + beta_rot <= 1, beta = |E_rot / E_pot|  (BBP95 eq. 2.10)
//   bound                   E_tot = E_kin + E_th + E_pot < 0
// A candidate denser than SinkParams::forced_creation_factor x rho_sink (when that is > 0) passes
// every check after the first (Phantom's f_crit_override: "forcing sink formation despite tests
// not passing"); SinkCreationTest::forced says so.
//
// The clump's energies (ClumpEnergies), relative to the clump's centre of mass x_c and its
// velocity v_c (Phantom measures them relative to the candidate instead):
//   E_kin = sum_j m_j |v_j - v_c|^2 / 2
//   E_rot = |(E_x, E_y, E_z)|, E_k = sum_j m_j (r_j x w_j)_k^2 / (2 |r_j,perp k|^2): the kinetic
//           energy of the motion about each axis k through x_c (r = x - x_c, w = v - v_c,
//           r_perp k = r without its k component); Phantom's definition. Note that
//           alpha + beta <= 1 can fail while E_tot < 0 only if E_rot > E_kin, which this
//           per-axis norm allows (up to sqrt(3) E_kin) but a plain sum of azimuthal energies
//           would not: the check then adds nothing to E_tot < 0.
//   E_th  = sum_j m_j u_j (u: specific thermal energy)
//   E_pot = sum over pairs j < k of the clump m_j m_k phi(|x_j - x_k|, h_j, h_k) (the clump's
//           self-gravity; no self-energy terms, which Phantom's exact branch includes)
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sphark/sinks/sink.hpp"

namespace sphark {

enum class SinkCheck {
  ok,
  no_candidate,             // no gas denser than rho_sink
  inside_existing_sink,     // within the creation radius of a sink
  diverging_flow,           // div v >= 0
  smoothing_length_too_large,  // 2 h >= r_acc
  not_potential_minimum,
  too_hot,                  // alpha > 1/2
  too_hot_and_rotating,     // alpha + beta > 1
  unbound,                  // E_tot >= 0
};
std::string to_string(SinkCheck c);

struct ClumpEnergies {
  Real kinetic = 0, rotational = 0, thermal = 0, potential = 0;
  Real total() const { return kinetic + thermal + potential; }
  // +infinity for a clump without potential energy (a lone particle): never created
  Real alpha() const { return potential != 0 ? std::abs(thermal / potential) : HUGE_VAL; }
  Real beta() const { return potential != 0 ? std::abs(rotational / potential) : HUGE_VAL; }
};

// The densest gas particle if its density exceeds rho_sink (ties: the lowest index).
std::optional<std::size_t> densest_gas_particle(const GasView& gas, Real rho_sink);

// Indices j (ascending, the candidate included) with |x_j - x_i| < radius (minimum image if
// params.box). Needs gas.x.
std::vector<std::uint32_t> clump_members(const GasView& gas, std::size_t candidate, Real radius,
                                         const std::optional<PeriodicBox<3>>& box);

// Needs gas.x, v, mass, h, u.
ClumpEnergies clump_energies(const GasView& gas, const std::vector<std::uint32_t>& clump, const SinkParams& params);

SinkCheck check_outside_existing_sinks(const GasView& gas, std::size_t candidate, const std::vector<Sink>& sinks,
                                       const SinkParams& params);
SinkCheck check_converging_flow(const GasView& gas, std::size_t candidate);                  // needs div_v
SinkCheck check_smoothing_length(const GasView& gas, std::size_t candidate, Real r_acc);     // needs h
SinkCheck check_potential_minimum(const GasView& gas, std::size_t candidate,
                                  const std::vector<std::uint32_t>& clump);                 // needs phi
SinkCheck check_thermal(const ClumpEnergies& e);
SinkCheck check_thermal_and_rotation(const ClumpEnergies& e);
SinkCheck check_bound(const ClumpEnergies& e);

struct SinkCreationTest {
  SinkCheck result = SinkCheck::no_candidate;  // ok, or the first check that failed (order above)
  std::size_t candidate = 0;
  std::vector<std::uint32_t> clump;            // candidate + gas within r_acc (the sink's mass)
  ClumpEnergies energies;                      // set once the cheap checks have passed
  bool forced = false;                         // made by SinkParams::forced_creation_factor
};

// Runs the checks in the order of the list above (the cheap ones first). Throws
// std::invalid_argument if a needed array is null or r_acc <= 0.
SinkCreationTest test_sink_creation(const GasView& gas, const std::vector<Sink>& sinks, const SinkParams& params);

// The sink made of the clump: mass, momentum, centre of mass, and the clump's angular momentum
// about that centre as spin (mass, linear and angular momentum conserved to round-off).
Sink sink_from_clump(const GasView& gas, const std::vector<std::uint32_t>& clump, Real r_acc,
                     const std::optional<PeriodicBox<3>>& box);

// The sinks after a new one made of `clump` (sink_from_clump) is appended, the clump removed.
SinkUpdate sink_made_of(const GasView& gas, const std::vector<Sink>& sinks, const std::vector<std::uint32_t>& clump,
                        const SinkParams& params);

// test_sink_creation and, if it passes, the new sink appended (its clump removed).
// result.removed is empty when no sink was created; *test (if given) is the test made.
SinkUpdate create_sink_if_allowed(const GasView& gas, const std::vector<Sink>& sinks, const SinkParams& params,
                                  SinkCreationTest* test = nullptr);

}  // namespace sphark
