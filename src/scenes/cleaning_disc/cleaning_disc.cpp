#include "sphark/scenes/cleaning_disc/cleaning_disc.hpp"

#include <cmath>

namespace sphark {

void disc_initial_field(const SpmhdScheme<2>& s, const ParticleSet2D& p, Real* y) {
  const StateLayout& L = s.layout();
  const Real b0 = 1.0 / std::sqrt(4 * kPi), r0 = 1.0 / std::sqrt(8.0);
  auto B = vector_field<3>(y, L, Field::MagneticField);
  for (std::size_t a = 0; a < p.size(); ++a) {
    const Real q = std::hypot(p.x[2 * a], p.x[2 * a + 1]) / r0;
    const Real q4 = q * q * q * q;
    B(0, a) = q < 1 ? b0 * (q4 * q4 - 2 * q4 + 1) : 0.0;  // seed 000, eq. (40)
    B(1, a) = 0;
    B(2, a) = b0;
  }
  if (L.has(Field::Psi)) scalar_field(y, L, Field::Psi).setZero();
}

const std::vector<CleaningDiscVariant>& cleaning_disc_variants() {
  static const std::vector<CleaningDiscVariant> v = {{"constrained_sigma0", Cleaning::Constrained, false, true},
                                                     {"constrained_damped", Cleaning::Constrained, true, false},
                                                     {"nonconservative_sigma0", Cleaning::NonConservative, false, true},
                                                     {"nonconservative_damped", Cleaning::NonConservative, true, false}};
  return v;
}

namespace {
// The options with c_h frozen at the fastest wave speed of the initial field (a probe).
SpmhdOptions disc_options(const ParticleSet2D& p, Cleaning form, Real sigma, Real courant) {
  SpmhdOptions o;
  o.evolve_particles = false;
  o.cleaning = form;
  o.sigma = sigma;
  o.courant = courant;
  SpmhdScheme<2> probe(p.m, o, std::nullopt, p.x);
  std::vector<Real> y0(probe.size(), 0);
  disc_initial_field(probe, p, y0.data());
  probe.evaluate(0, y0.data());
  o.fixed_ch = probe.cleaning_speed();
  return o;
}
}  // namespace

CleaningDisc::CleaningDisc(Cleaning form, Real sigma, Real spacing, Real courant)
    : particles(disc_square_lattice(1.0, spacing, 1.0)),
      scheme(particles.m, disc_options(particles, form, sigma, courant), std::nullopt, particles.x),
      y0(scheme.size(), 0) {
  disc_initial_field(scheme, particles, y0.data());
}

}  // namespace sphark
