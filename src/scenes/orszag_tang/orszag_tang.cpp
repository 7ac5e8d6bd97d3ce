#include "sphark/scenes/orszag_tang/orszag_tang.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sphark {

PeriodicBox<2> unit_periodic_box() {
  PeriodicBox<2> box;
  box.periodic = {true, true};
  return box;
}

void orszag_tang_initial_state(const SpmhdScheme<2>& s, const ParticleSet2D& p, Real* y) {
  const StateLayout& L = s.layout();
  const Real b0 = 1.0 / std::sqrt(4 * kPi), two_pi = 2 * kPi;
  const Real u0 = kOrszagTangPressure / ((s.options().gamma - 1) * kOrszagTangRho);
  auto x = vector_field<2>(y, L, Field::Position);
  auto v = vector_field<2>(y, L, Field::Velocity);
  auto u = scalar_field(y, L, Field::InternalEnergy);
  for (std::size_t a = 0; a < p.size(); ++a) {
    const Real px = p.x[2 * a], py = p.x[2 * a + 1];
    x(0, a) = px;
    x(1, a) = py;
    v(0, a) = -std::sin(two_pi * py);
    v(1, a) = std::sin(two_pi * px);
    u(a) = u0;
  }
  if (L.has(Field::MagneticField)) {
    auto B = vector_field<3>(y, L, Field::MagneticField);
    for (std::size_t a = 0; a < p.size(); ++a) {
      B(0, a) = -b0 * std::sin(two_pi * p.x[2 * a + 1]);
      B(1, a) = b0 * std::sin(2 * two_pi * p.x[2 * a]);
      B(2, a) = 0;
    }
  }
  if (L.has(Field::EulerAlpha)) {
    auto alpha = scalar_field(y, L, Field::EulerAlpha);
    for (std::size_t a = 0; a < p.size(); ++a)
      alpha(a) = b0 * (std::cos(2 * two_pi * p.x[2 * a]) / (2 * two_pi) + std::cos(two_pi * p.x[2 * a + 1]) / two_pi);
  }
  if (L.has(Field::Psi)) scalar_field(y, L, Field::Psi).setZero();
}

const std::vector<std::string>& orszag_tang_variants() {
  static const std::vector<std::string> v = {"none", "resistivity", "euler", "cleaning", "cleaning+resistivity"};
  return v;
}

SpmhdOptions orszag_tang_options(const std::string& v, const OrszagTangParams& p) {
  const auto& all = orszag_tang_variants();
  if (std::find(all.begin(), all.end(), v) == all.end()) throw std::invalid_argument("unknown Orszag-Tang variant '" + v + "'");
  SpmhdOptions o;
  o.gamma = 5.0 / 3.0;
  o.courant = p.courant;
  if (v == "resistivity" || v == "cleaning+resistivity") o.alpha_b = p.alpha_b;
  if (v == "euler") o.field = FieldRepresentation::EulerPotentials;
  if (v == "cleaning" || v == "cleaning+resistivity") {
    o.cleaning = Cleaning::Constrained;
    o.sigma = p.sigma;
    o.overclean = p.overclean;
    o.local_ch = p.local_ch;
    o.cleaning_courant = p.cleaning_courant;
  }
  o.skin = p.skin;
  o.h_initial = o.eta * std::sqrt(1.0 / (static_cast<Real>(p.nx) * hexagonal_rows(p.nx)));
  return o;
}

OrszagTang::OrszagTang(const std::string& variant, const OrszagTangParams& params)
    : nx(params.nx),
      ny(hexagonal_rows(params.nx)),
      particles(hexagonal_lattice_unit_box(nx, ny, kOrszagTangRho)),
      scheme(particles.m, orszag_tang_options(variant, params), unit_periodic_box()),
      y0(scheme.size(), 0) {
  orszag_tang_initial_state(scheme, particles, y0.data());
}

}  // namespace sphark
