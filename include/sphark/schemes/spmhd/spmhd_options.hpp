#pragma once
// Options of the SPMHD scheme (seed 000, §II). Units: mu0 = 1 (magnetic pressure B^2/2).
#include <string>
#include <string_view>

#include "sphark/core/types.hpp"
#include <optional>

#include "sphark/gravity/point_mass_gravity.hpp"
#include "sphark/gravity/self_gravity.hpp"
#include "sphark/operators/barotropic_eos.hpp"

namespace sphark {

enum class Cleaning {
  None,             // no psi field
  Constrained,      // seed 000: div B by (20), grad psi by its conjugate (23), dpsi/dt by (19)+(25)
  NonConservative,  // the previous form: difference operators for both, no -psi div v / 2 term
};

enum class FieldRepresentation {
  MagneticField,   // evolve B by the induction equation (7)
  EulerPotentials  // B = grad alpha x grad beta, alpha and beta advected (2D: beta = z, only alpha)
};

// The densities that a subset evaluation (rhs_subset: block steps, multirate) gives the active
// particles' neighbours that are not active themselves.
enum class SubsetDensity {
  Solved,    // solved at the evaluation's positions, as the active particles' (seed 000, eqs. (4)-(5))
  Predicted  // h advanced by dh/dt = h div v / D from its last solve and rho = m (eta / h)^D (eq. (5)),
             // Omega and zeta kept from that solve: each evaluation solves only the active
             // particles (Phantom's individual time steps keep the inactive particles' last density)
};

struct SpmhdOptions {
  Real gamma = 5.0 / 3.0;       // adiabatic index, P = (gamma - 1) rho u
  // A barotropic gas P = P(rho) (Price & Bate 2007; operators/barotropic_eos.hpp) instead: the
  // state then holds no internal energy, and the conductivity (alpha_u) is off.
  std::optional<BarotropicEosParams> barotropic;
  Real eta = 1.2;               // h = eta (m/rho)^(1/D), seed 000 eq. (5)
  Real h_tolerance = 1e-10;     // relative Newton tolerance on h
  Real h_initial = 0;           // first guess for h (0: from the bounding box and N)
  // The largest h (SWIFT's SPH:h_max): a particle whose root of (4)-(5) lies beyond takes h_max,
  // its density the sum (4) there and Omega = 1 (its h then does not depend on rho; the grad-h
  // terms vanish, the pair forces stay antisymmetric). 0: in a periodic box half the shortest
  // period / (1.5 support) (room for a list skin of 0.5 in the minimum image), none otherwise;
  // +inf: none (a support beyond half the box is then an error).
  Real h_max = 0;

  bool evolve_particles = true; // false: the cleaning subsystem only (fixed particles, state B, psi)
  FieldRepresentation field = FieldRepresentation::MagneticField;
  Cleaning cleaning = Cleaning::None;
  Real sigma = 0.3;             // damping: 1/tau = sigma c_h / h (seed 000, §I)
  Real fixed_ch = 0;            // > 0: use this c_h; else c_h = max fast magnetosonic speed per RHS
  Real overclean = 1;           // c_h = overclean x (fixed_ch or max fast speed), >= 1 (Phantom's overcleanfac;
                                // Tricco, Price & Bate 2016). The damping 1/tau = sigma c_h / h and the
                                // time step C h / max(c_h, v_sig) use this c_h.
  bool local_ch = false;        // per-particle c_h,a = overclean x fast speed of a, with the state holding
                                // psi / c_h (Tricco, Price & Bate 2016); false: one global c_h
  // local_ch: c_h,a = overclean x the largest fast speed within ch_spread kernel supports of a
  // (hops of |x_ab| < support max(h_a, h_b)); 0: a's own. The induction's -grad(c_h psi/c_h) has a
  // part (psi/c_h) grad c_h that makes div B where c_h jumps (a cloud's surface, the sound speed
  // x sqrt(30)); spread over two supports the jump no longer does (docs/cloud_collapse.md).
  int ch_spread = 0;

  bool subtract_monopole_force = true;  // seed 000, eq. (9)
  // eq. (9) left out for gas closer than this to a sink (0: applied everywhere): next to an
  // accretion radius the field's support has a hole and h|div B|/|B| is O(1) (docs/cloud_collapse.md)
  Real tensile_sink_exclusion = 0;
  // eq. (9) weighted by plasma beta = 2P/|B|^2 (Phantom's switch, force.F90 since 2018): whole
  // below tensile_beta_full, falling linearly to nothing at tensile_beta_none; 0: applied at every beta
  Real tensile_beta_full = 2;
  Real tensile_beta_none = 0;
  Real alpha_visc = 1.0;        // artificial viscosity (0 = off)
  Real beta_visc = 2.0;         // signal velocity v_sig = (c_a + c_b)/2 - beta w_ab for w_ab < 0
  Real alpha_u = 1.0;           // artificial thermal conductivity (0 = off), v_sig = sqrt(|dP|/rho_ab)
  Real alpha_b = 0.0;           // artificial resistivity, seed 000 eq. (10) (0 = off)

  Real courant = 0.3;           // for max_stable_dt: C h / v_sig
  // The cleaning wave's own Courant number: max_stable_dt = min(C h / (c_f + (1 + beta) |v|),
  // C_h h / (c_h + (1 + beta) |v|)); 0 = C (then the one criterion C h / (max(c_f, c_h) + (1 + beta) |v|)).
  Real cleaning_courant = 0;

  // Self-gravity (3D): kernel softening with each particle's own h and the grad-h term (Price &
  // Monaghan 2007; gravity/), isolated boundaries even in a periodic box (no Ewald sum).
  bool self_gravity = false;
  GravitySolver gravity_solver = GravitySolver::Tree;
  Real G = 1;                   // gravitational constant in code units
  Real gravity_theta = kDefaultFixedTheta;  // tree opening angle (the root's with GravityOpening::Mass)
  GravityOpening gravity_opening = GravityOpening::Fixed;
  Real force_courant = 0.25;    // with gravity, max_stable_dt also <= force_courant sqrt(h / |a|)
  // Sink particles (a second species: position, velocity, mass, spin; none at first), with
  // gravity on the gas and on each other (gravity/point_mass_gravity.hpp). Created and fed
  // between steps (sinks/sink_events.hpp).
  bool sink_particles = false;
  SinkSoftening sink_softening;
  // The density solve starts from the last h advanced by dh/dt = h div v / D (false: from the
  // last h). Only the initial guess: the roots agree to the solve's tolerance.
  bool predict_h = true;
  SubsetDensity subset_density = SubsetDensity::Solved;
  Real skin = 0.25;             // Verlet skin: particle i lists neighbours within 2 h_i (1 + skin)
  // The part of the skin that scales with each particle's own h; the rest is one length for all,
  // (1 - f) skin h_min: particle i lists neighbours within 2 [h_i (1 + f skin) + (1 - f) skin h_min]
  // (h_min the smallest h at the build). The smallest h's skin, which sets how far particles may
  // move before a rebuild, is skin whatever f; with h spanning decades (a collapse) f < 1 makes
  // the large-h particles' lists far shorter. 1: the skin of each h in proportion.
  Real skin_own_fraction = 1;
};

// Self-gravity on (3D) with the solver and the tree's opening (docs/gravity.md).
void enable_self_gravity(SpmhdOptions& o, GravitySolver solver, Real theta, GravityOpening opening);
// Sinks whose gravity is softened with the cubic spline inside the accretion radius r_acc
// (h = r_acc / 2, Newtonian beyond): gas inside r_acc that the checks do not accrete yet feels a
// finite force.
void enable_kernel_softened_sinks(SpmhdOptions& o, Real accretion_radius);

// "none", "constrained", "nonconservative"
Cleaning parse_cleaning(std::string_view s);
std::string_view cleaning_name(Cleaning c);
// "solved", "predicted"
SubsetDensity parse_subset_density(std::string_view s);
std::string_view subset_density_name(SubsetDensity d);

}  // namespace sphark
