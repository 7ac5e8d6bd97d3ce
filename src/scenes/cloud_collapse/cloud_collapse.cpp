#include "sphark/scenes/cloud_collapse/cloud_collapse.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sphark/analytic/free_fall.hpp"
#include "sphark/gravity/kernel_softening.hpp"
#include "sphark/operators/barotropic_eos.hpp"
#include "sphark/sinks/sink_run.hpp"

namespace sphark {

const std::vector<std::string>& cloud_collapse_variants() {
  static const std::vector<std::string> v = {"none", "cleaning", "cleaning+resistivity"};
  return v;
}

Real critical_mass_to_flux_cgs() { return 0.53 / (3 * kPi) * std::sqrt(5 / cgs::gravitational_constant); }

Real field_for_mass_to_flux_gauss(Real mass_g, Real radius_cm, Real mu) {
  return mass_g / (kPi * radius_cm * radius_cm * mu * critical_mass_to_flux_cgs());
}

CloudNumbers cloud_numbers(const CloudCollapseParams& p, const CodeUnits& u) {
  for (Real v : {p.mass_msun, p.radius_cm, p.sound_speed_cm_s, p.mass_to_flux, p.rho_sink_g_cm3, p.accretion_radius_cm,
                 p.box_over_radius})
    if (!(v > 0)) throw std::invalid_argument("cloud collapse: physical inputs must be positive");
  if (!(p.omega_rad_s >= 0) || !(p.density_contrast >= 1))
    throw std::invalid_argument("cloud collapse: need omega >= 0 and a density contrast >= 1");
  CloudNumbers c;
  const Real mass_g = p.mass_msun * cgs::solar_mass;
  c.mass = u.mass(mass_g);
  c.radius = u.length(p.radius_cm);
  c.density = c.mass / (4.0 / 3.0 * kPi * c.radius * c.radius * c.radius);
  c.sound_speed = u.velocity(p.sound_speed_cm_s);
  c.omega = p.omega_rad_s * u.time_s();
  c.field = u.magnetic_field(field_for_mass_to_flux_gauss(mass_g, p.radius_cm, p.mass_to_flux));
  c.free_fall_time = free_fall_time(c.density);
  c.rho_sink = u.density(p.rho_sink_g_cm3);
  c.accretion_radius = u.length(p.accretion_radius_cm);
  return c;
}

SpmhdOptions cloud_collapse_options(const CloudCollapseParams& p, const CloudNumbers& c, const CodeUnits& u) {
  const auto& variants = cloud_collapse_variants();
  if (std::find(variants.begin(), variants.end(), p.variant) == variants.end())
    throw std::invalid_argument("unknown cloud-collapse variant '" + p.variant + "' (none, cleaning, cleaning+resistivity)");
  SpmhdOptions o;
  o.barotropic = sphere_in_box_params(u, p.sound_speed_cm_s, c.density * u.density_g_cm3(), p.density_contrast);
  o.eta = 1.2;  // Phantom hfact
  o.alpha_visc = p.alpha_visc;
  o.alpha_u = 0;
  o.subtract_monopole_force = p.tensile_correction;
  o.tensile_sink_exclusion = p.tensile_exclusion * c.accretion_radius;
  o.tensile_beta_none = p.tensile_beta_none;
  if (p.variant != "none") {
    o.cleaning = Cleaning::Constrained;
    o.sigma = p.sigma;
    o.overclean = p.overclean;
    o.local_ch = p.local_ch;
    o.ch_spread = p.ch_spread;
  }
  if (p.variant == "cleaning+resistivity") o.alpha_b = p.alpha_b;
  o.courant = p.courant;
  o.cleaning_courant = p.cleaning_courant;
  o.force_courant = p.force_courant;
  enable_self_gravity(o, p.gravity, p.theta, p.opening);
  o.subset_density = p.subset_density;
  o.skin = p.skin;
  o.skin_own_fraction = p.skin_own_fraction;
  o.G = 1;
  enable_kernel_softened_sinks(o, c.accretion_radius);
  return o;
}

SinkParams cloud_sink_params(const CloudCollapseParams& p, const CloudNumbers& c) {
  SinkParams s;
  s.rho_sink = c.rho_sink;
  s.accretion_radius = c.accretion_radius;
  s.creation_radius = p.creation_radius_over_racc * c.accretion_radius;
  s.forced_creation_factor = p.forced_sink_factor;
  s.G = 1;
  // the gravity solver's kernel-softened pair potential, symmetrised (Phantom's ptmass_create)
  s.pair_potential = cubic_spline_pair_potential();
  const Real half = 0.5 * p.box_over_radius * c.radius;
  PeriodicBox<3> box;
  box.lo = Vec<3>::Constant(-half);
  box.hi = Vec<3>::Constant(half);
  box.periodic = {true, true, true};
  s.box = box;
  return s;
}

namespace {

SphereInBox place(const CloudCollapseParams& p, const CloudNumbers& c) {
  if (p.particles < 1) throw std::invalid_argument("cloud collapse: need at least one sphere particle");
  SphereSpec spec;
  spec.particles = p.particles;
  spec.radius = c.radius;
  spec.mass = c.mass;
  return sphere_in_box(spec, p.box_over_radius, p.density_contrast, BoxFit::exact_side);
}

std::vector<Real> all_positions(const SphereInBox& s) {
  std::vector<Real> x = s.sphere.x;
  x.insert(x.end(), s.ambient.begin(), s.ambient.end());
  return x;
}

}  // namespace

CloudCollapse::CloudCollapse(const CloudCollapseParams& p)
    : numbers(cloud_numbers(p, units)),
      placement(place(p, numbers)),
      box(*cloud_sink_params(p, numbers).box),
      scheme(std::vector<Real>(placement.sphere.size() + placement.ambient.size() / 3, placement.sphere.particle_mass),
             cloud_collapse_options(p, numbers, units), box),
      sinks(cloud_sink_params(p, numbers)),
      y0(scheme.size(), 0) {
  const StateLayout& L = scheme.layout();
  const std::vector<Real> x = all_positions(placement);
  std::copy(x.begin(), x.end(), y0.begin() + static_cast<std::ptrdiff_t>(L.offset(Field::Position)));
  auto v = vector_field<3>(y0.data(), L, Field::Velocity);
  auto B = vector_field<3>(y0.data(), L, Field::MagneticField);
  for (std::size_t a = 0; a < scheme.particles(); ++a) {
    B(2, a) = numbers.field;
    if (a < sphere_particles()) {  // v = Omega z x r
      v(0, a) = -numbers.omega * x[3 * a + 1];
      v(1, a) = numbers.omega * x[3 * a];
    }
  }
}

}  // namespace sphark
