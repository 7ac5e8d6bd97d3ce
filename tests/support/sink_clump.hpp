#pragma once
// A self-gravitating, magnetised, rotating clump with a sink particle (every SPMHD term on), for
// the tests of the multirate interface (tests/spmhd/spmhd_subsets_test.cpp) and of the block
// steps with a sink (tests/multirate/block_sinks_test.cpp).
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "sphark/initial/spheres.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "clump_state.hpp"

namespace sphark::test {

struct Clump {
  std::unique_ptr<SpmhdScheme<3>> scheme;
  std::vector<Real> y;
};

// 300 particles of an Evrard sphere, converging and rotating, with B, psi, tree gravity, and
// particle 0 turned into a sink of three particle masses; eq. (9) left out within
// tensile_exclusion of the sink and weighted by plasma beta between beta_full and beta_none
// (SpmhdOptions::tensile_beta_full, tensile_beta_none; 0: at every beta).
// fixed_ch > 0: that cleaning speed (else the largest fast speed, global).
inline Clump clump(Real tensile_exclusion = 0, Real beta_full = 2, Real beta_none = 0, Real fixed_ch = 0) {
  SphereSpec spec;
  spec.particles = 300;
  spec.radius = 0.1;
  const ParticlePlacement place = evrard_sphere(spec);
  const std::size_t n = place.size();
  SpmhdOptions o;
  o.cleaning = Cleaning::Constrained;
  o.alpha_b = 1.0;
  o.self_gravity = true;
  o.gravity_solver = GravitySolver::Tree;
  o.sink_particles = true;
  o.tensile_sink_exclusion = tensile_exclusion;
  o.tensile_beta_full = beta_full;
  o.tensile_beta_none = beta_none;
  o.fixed_ch = fixed_ch;
  Clump c{std::make_unique<SpmhdScheme<3>>(std::vector<Real>(n, place.particle_mass), o), {}};
  SpmhdScheme<3>& s = *c.scheme;
  std::vector<Real> all(s.size(), 0), scratch(s.size());
  const StateLayout before = s.layout();
  test::fill_clump_gas(place, before, all);
  EXPECT_EQ(s.rhs(0, all.data(), scratch.data()), 0) << s.last_error();  // h of every particle
  std::vector<std::size_t> kept;
  for (std::size_t a = 1; a < n; ++a) kept.push_back(a);
  s.change_particles(kept, 1);
  const StateLayout& L = s.layout();
  c.y.assign(s.size(), 0);
  for (Field f : L.fields(Species::Gas)) {
    const int comps = L.components(Species::Gas, f);
    for (std::size_t i = 0; i < kept.size(); ++i)
      for (int k = 0; k < comps; ++k) c.y[L.offset(f) + comps * i + k] = all[before.offset(f) + comps * kept[i] + k];
  }
  for (int k = 0; k < 3; ++k) {
    c.y[L.offset(Species::Sink, Field::Position) + k] = all[before.offset(Field::Position) + k];
    c.y[L.offset(Species::Sink, Field::Velocity) + k] = all[before.offset(Field::Velocity) + k];
  }
  c.y[L.offset(Species::Sink, Field::Mass)] = 3 * place.particle_mass;
  return c;
}

}  // namespace sphark::test
