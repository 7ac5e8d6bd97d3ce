#pragma once
// The oscillating elliptic water drop of seed 000, §IV-D: a disc of radius R on a square
// lattice (offset by half a spacing: 1976 particles for R = 1, spacing 0.04), rho0 = 1000,
// v = (-A x, A y), radial body force -omega^2 r, weakly compressible SPH (eqs. (26)-(28)) with
// optional constrained velocity cleaning (eqs. (29)-(30)).
#include <memory>
#include <string>
#include <vector>

#include "sphark/analytic/elliptic_drop.hpp"
#include "sphark/core/types.hpp"
#include "sphark/diagnostics/wcsph_diagnostics.hpp"
#include "sphark/integrate/ode_system.hpp"
#include "sphark/parallel/communicator.hpp"
#include "sphark/schemes/wcsph/wcsph_params.hpp"
#include "sphark/schemes/wcsph/wcsph_system.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark {

struct WaterDropConfig {
  Real radius = 1.0;
  Real spacing = 0.04;
  Real amplitude = 100.0;    // A of v = (-A x, A y)
  Real omega = 100.0;        // body force -omega^2 r
  Real rho0 = 1000.0;
  Real sound_speed = 1400.0;
  Real h_factor = 2.0;       // h = h_factor * spacing  (eq. (5) with eta = h_factor, m = rho0 dx^2)
  std::string kernel = "wendland_c2";
  Real alpha = 0.0;          // artificial viscosity
  bool diffusion_correction = true;  // Antuono et al. (2010) form of the density diffusion
  Real delta = 0.05;         // density diffusion
  bool cleaning = true;
  Real clean_sigma = 0.5;
  Real cfl = 0.25;
  // Verlet skin of the neighbour lists, a fraction of the support radius: a cost, not a result
  // (the pairs inside the support, and their order, do not depend on it). 0.3: 318 list builds
  // in a default run instead of 806 at 0.1, 11 % less CPU (docs/water_drop.md, "Neighbour skin").
  Real skin = 0.3;
  // Initial density from the exact solution's pressure p = p0 (1 - r^2/R^2) through the inverse
  // Tait EOS (true), or rho = rho0 (false: starts out of equilibrium, launches a pressure wave).
  bool exact_initial_pressure = true;
};

// The drop's semi-axes measured as in the issue: 2 sqrt(<x^2>) about the centre of mass.
struct SemiAxes {
  Real x, y;
};
SemiAxes measure_semi_axes(const Real* positions, std::size_t n);
// Collective: of the particles of every rank (n on this one).
SemiAxes measure_semi_axes(const Communicator& comm, const Real* positions, std::size_t n);

// Common interface of the WCSPH system whatever its kernel (chosen at run time by name).
class WcsphModel {
 public:
  virtual ~WcsphModel() = default;
  virtual OdeSystem& system() = 0;
  virtual const StateLayout& layout() const = 0;
  virtual WcsphDiagnostics<2> diagnostics(Real t, const Real* y) = 0;
  // The VTK frame of (t, y) (diagnostics/wcsph_diagnostics.hpp); valid until the next call.
  virtual ParticleFrame frame(Real t, const Real* y) = 0;
  virtual long neighbour_builds() const = 0;
  // Distributed runs (WcsphSystem::distribute, set_particles): this rank's particles by global id.
  virtual void distribute(Communicator comm, std::vector<std::int64_t> ids) = 0;
  virtual void set_particles(std::vector<std::int64_t> ids) = 0;
};

struct WaterDrop {
  WaterDropConfig config;
  std::unique_ptr<WcsphModel> model;
  std::vector<Real> y0;   // initial state, laid out by model->layout()
  EllipticDrop exact;
  std::size_t particles() const { return model->layout().particles(); }
};

// Builds the drop; throws std::invalid_argument for bad configuration values.
WaterDrop make_water_drop(const WaterDropConfig& config);

// Per-entry absolute tolerances: `atol` times each field's natural scale (R for positions,
// V = max(A, omega) R for velocities, rho0 for density, rho0 c_s V for psi, which has units of
// pressure).
std::vector<Real> water_drop_absolute_tolerances(const WaterDrop& drop, Real atol);

// Kernels the scene accepts by name.
std::vector<std::string> wcsph_kernel_names();

}  // namespace sphark
