// The vector paths of the pair loops (simd/dispatch.hpp: SSE2, and AVX2 + FMA and AVX-512 where
// the CPU has them) against the scalar path, on a WCSPH drop (2D and 3D) and SPMHD states with every term on
// (2D Orszag-Tang, 3D disordered lattice; a barotropic gas, which has no internal energy; a
// self-gravitating clump with a sink particle, gravity's grad-h term included): every derivative
// field agrees to round-off, and each path gives the same result on 1 and 2 threads, bit for bit,
// and with the records written by streaming stores.
//
// The bound. A derivative is a sum of N pair terms; the paths add them in another order (lanes,
// then the lanes) and, with FMA, round a*b + c once instead of twice. Either changes the sum by
// at most about N eps sum_b |t_b| (eps = 2.2e-16). Measured as the largest difference in a field
// over its largest magnitude, with sum_b |t_b| <= N max|t| and max|t| / max|f| <= N (pair terms
// that cancel), the bound is N^2 eps: with N = 64 (the scenes below have 18-56 interacting
// neighbours on average) 64^2 eps = 9e-13, asserted as 1e-12. The SPMHD h solve sees the same
// reordering (h to round-off, then the same bound through the kernel). The measured differences
// are printed: 5e-16 .. 1.3e-14 (psi, whose rate cancels most) on this machine.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../spmhd/spmhd_checks.hpp"
#include "../support/clump_state.hpp"
#include "sphark/core/cache_hints.hpp"
#include "sphark/initial/spheres.hpp"
#include "sphark/scenes/orszag_tang/orszag_tang.hpp"
#include "sphark/scenes/water_drop/water_drop.hpp"
#include "sphark/simd/dispatch.hpp"

namespace sphark {
namespace {

constexpr Real kBound = 1e-12;

// Restores the path in use when a test ends.
struct PathGuard {
  PairLoopSimd before = pair_loop_simd();
  ~PathGuard() { use_pair_loop_simd(before); }
};

std::vector<PairLoopSimd> vector_paths() {
  std::vector<PairLoopSimd> paths{PairLoopSimd::Sse2};
  for (PairLoopSimd p : {PairLoopSimd::Avx2, PairLoopSimd::Avx512})
    if (static_cast<int>(p) <= static_cast<int>(widest_pair_loop_simd())) paths.push_back(p);
  return paths;
}

// max |a - b| / max |b| over the entries [begin, end) of a field.
Real relative_difference(const std::vector<Real>& a, const std::vector<Real>& b, std::size_t begin, std::size_t end) {
  Real diff = 0, scale = 0;
  for (std::size_t k = begin; k < end; ++k) {
    diff = std::max(diff, std::abs(a[k] - b[k]));
    scale = std::max(scale, std::abs(b[k]));
  }
  return scale > 0 ? diff / scale : diff;
}

// Every field of the layout: the vector path against the scalar one.
void expect_round_off(const StateLayout& L, const std::vector<Real>& simd, const std::vector<Real>& scalar,
                      const std::string& what) {
  for (Species sp : {Species::Gas, Species::Sink}) {
    if (!L.has(sp)) continue;
    for (Field f : {Field::Position, Field::Velocity, Field::Density, Field::InternalEnergy, Field::MagneticField,
                    Field::Psi}) {
      if (!L.has(sp, f) || L.field_size(sp, f) == 0) continue;
      const std::size_t o = L.offset(sp, f);
      const Real d = relative_difference(simd, scalar, o, o + L.field_size(sp, f));
      const std::string name = sp == Species::Gas ? std::string(f.name()) : "sink " + std::string(f.name());
      std::printf("  %-28s d/dt %-16s max |difference| / max |value| = %.2e\n", what.c_str(), name.c_str(), d);
      EXPECT_LE(d, kBound) << what << ", d/dt " << name;
    }
  }
}

void expect_identical(const std::vector<Real>& a, const std::vector<Real>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << what << ", entry " << k;
}

// rhs of a fresh system made by make() at its initial state, on the given path and thread count.
template <class Make>
std::vector<Real> rhs_on(PairLoopSimd path, int threads, Make&& make) {
  use_pair_loop_simd(path);
  omp_set_num_threads(threads);
  auto [system, y] = make();
  std::vector<Real> ydot(y.size());
  EXPECT_EQ(system->rhs(0, y.data(), ydot.data()), 0) << system->last_error();
  omp_set_num_threads(1);
  return ydot;
}

template <class Make>
void compare_paths(const StateLayout& layout, const std::string& scene, Make&& make) {
  PathGuard guard;
  const std::vector<Real> scalar = rhs_on(PairLoopSimd::Scalar, 1, make);
  expect_identical(scalar, rhs_on(PairLoopSimd::Scalar, 2, make), scene + " scalar, 2 threads");
  for (PairLoopSimd path : vector_paths()) {
    const std::string name = scene + " " + std::string(pair_loop_simd_name(path));
    const std::vector<Real> one = rhs_on(path, 1, make);
    expect_round_off(layout, one, scalar, name);
    expect_identical(one, rhs_on(path, 2, make), name + ", 2 threads");
  }
  // the records written with streaming stores (core/cache_hints.hpp; by default only above 16 MB)
  const std::vector<Real> cached = rhs_on(widest_pair_loop_simd(), 2, make);
  const std::size_t threshold = stream_records_above();
  stream_records_above() = 0;
  const std::vector<Real> streamed = rhs_on(widest_pair_loop_simd(), 2, make);
  stream_records_above() = threshold;
  expect_identical(cached, streamed, scene + ", records streamed");
}

// The drop with viscosity and the corrected density diffusion on (every WCSPH term), moved off
// its lattice.
TEST(PairLoopPaths, WcsphDrop2D) {
  auto make = [] {
    WaterDropConfig c;
    c.alpha = 0.1;
    WaterDrop drop = make_water_drop(c);
    auto x = vector_field<2>(drop.y0.data(), drop.model->layout(), Field::Position);
    for (Index a = 0; a < x.cols(); ++a) x.col(a) += 0.003 * Vec<2>(std::cos(a), std::sin(1.7 * a));
    struct Made {
      std::shared_ptr<WaterDrop> drop;
      OdeSystem* operator->() const { return &drop->model->system(); }
    };
    auto owned = std::make_shared<WaterDrop>(std::move(drop));
    return std::pair{Made{owned}, owned->y0};
  };
  const StateLayout layout = make_water_drop(WaterDropConfig{}).model->layout();
  compare_paths(layout, "WCSPH drop 2D", make);
}

TEST(PairLoopPaths, Wcsph3D) {
  auto make = [] {
    const int nx = 9;
    const Real dx = 1.0 / nx, h = 1.3 * dx;
    WcsphParams<3> p;
    p.mass = 1000 * dx * dx * dx, p.h = h, p.alpha = 0.1, p.cleaning = true;
    auto sys = std::make_shared<WcsphSystem<3, WendlandC2<3>>>(std::size_t(nx * nx * nx), p);
    std::vector<Real> y(sys->size());
    auto x = vector_field<3>(y.data(), sys->layout(), Field::Position);
    auto v = vector_field<3>(y.data(), sys->layout(), Field::Velocity);
    auto rho = scalar_field(y.data(), sys->layout(), Field::Density);
    auto psi = scalar_field(y.data(), sys->layout(), Field::Psi);
    for (Index a = 0; a < x.cols(); ++a) {
      x.col(a) = dx * Vec<3>(a % nx + 0.1 * std::sin(a), a / nx % nx + 0.1 * std::cos(a), a / (nx * nx));
      v.col(a) = Vec<3>(std::sin(0.3 * a), std::cos(0.7 * a), std::sin(1.1 * a));
      rho[a] = 1000 * (1 + 0.01 * std::sin(0.9 * a));
      psi[a] = 1e3 * std::cos(0.4 * a);
    }
    return std::pair{sys, y};
  };
  WcsphParams<3> p;
  p.mass = p.h = 1, p.cleaning = true;
  const StateLayout layout = WcsphSystem<3, WendlandC2<3>>(9 * 9 * 9, p).layout();
  compare_paths(layout, "WCSPH lattice 3D", make);
}

SpmhdOptions every_term() {
  SpmhdOptions o;
  o.cleaning = Cleaning::Constrained;
  o.alpha_b = 1.0;  // viscosity and conductivity are on by default
  return o;
}

TEST(PairLoopPaths, SpmhdOrszagTang2D) {
  const int nx = 24;
  auto make = [nx] {
    ParticleSet2D p = hexagonal_lattice_unit_box(nx, hexagonal_rows(nx), kOrszagTangRho);
    SpmhdOptions o = every_term();
    o.h_initial = o.eta / std::sqrt(static_cast<Real>(nx * hexagonal_rows(nx)));
    auto s = std::make_shared<SpmhdScheme<2>>(p.m, o, unit_periodic_box());
    std::vector<Real> y(s->size());
    orszag_tang_initial_state(*s, p, y.data());
    auto psi = scalar_field(y.data(), s->layout(), Field::Psi);
    for (Index a = 0; a < psi.size(); ++a) psi[a] = 0.01 * std::sin(0.37 * a);
    return std::pair{s, y};
  };
  compare_paths(make().first->layout(), "SPMHD Orszag-Tang 2D", make);
}

TEST(PairLoopPaths, SpmhdLattice3D) {
  const test::LatticeCase c{6, 0.3, false, 11};
  auto make = [c] {
    auto s = std::make_shared<SpmhdScheme<3>>(test::lattice_masses<3>(c), every_term(), test::unit_box<3>());
    return std::pair{s, test::lattice_state(*s, c)};
  };
  compare_paths(make().first->layout(), "SPMHD lattice 3D", make);
}

// A barotropic gas (no u in the state, no du/dt) with viscosity, resistivity and cleaning on.
TEST(PairLoopPaths, SpmhdBarotropicLattice3D) {
  const test::LatticeCase c{6, 0.3, false, 13};
  SpmhdOptions o = every_term();
  BarotropicEosParams eos;  // isothermal, then gamma = 7/5 from rho = 1.05 (the lattice straddles it)
  eos.sound_speed = 1, eos.rho1 = 1.05, eos.rho2 = 10, eos.rho3 = 100, eos.rho4 = 1000;
  o.barotropic = eos;
  auto make = [c, o] {
    auto s = std::make_shared<SpmhdScheme<3>>(test::lattice_masses<3>(c), o, test::unit_box<3>());
    SpmhdOptions adiabatic = o;  // the lattice state without u: from an adiabatic twin
    adiabatic.barotropic.reset();
    const SpmhdScheme<3> twin(test::lattice_masses<3>(c), adiabatic, test::unit_box<3>());
    const std::vector<Real> y_twin = test::lattice_state(twin, c);
    std::vector<Real> y(s->size());
    for (Field f : s->layout().fields())
      std::copy_n(y_twin.begin() + static_cast<std::ptrdiff_t>(twin.layout().offset(f)), s->layout().field_size(f),
                  y.begin() + static_cast<std::ptrdiff_t>(s->layout().offset(f)));
    return std::pair{s, y};
  };
  const StateLayout layout = make().first->layout();
  ASSERT_FALSE(layout.has(Field::InternalEnergy));
  compare_paths(layout, "SPMHD barotropic 3D", make);
}

// A converging, rotating, magnetised clump with self-gravity (direct summation: the softened
// forces and the grad-h term with zeta from the h solve) and a sink particle (change_particles),
// every hydrodynamic and MHD term on.
TEST(PairLoopPaths, SpmhdGravityAndSink3D) {
  SphereSpec spec;
  spec.particles = 300;
  spec.radius = 0.1;
  const ParticlePlacement place = evrard_sphere(spec);
  const std::size_t n = place.size();
  SpmhdOptions o = every_term();
  o.self_gravity = true;
  o.gravity_solver = GravitySolver::Direct;
  o.sink_particles = true;
  auto make = [&place, n, o] {
    auto s = std::make_shared<SpmhdScheme<3>>(std::vector<Real>(n, place.particle_mass), o);
    std::vector<Real> all(s->size(), 0), scratch(s->size());
    test::fill_clump_gas(place, s->layout(), all);
    EXPECT_EQ(s->rhs(0, all.data(), scratch.data()), 0) << s->last_error();  // h of every particle
    // particle 0 becomes a sink of three particle masses at its place
    std::vector<std::size_t> kept;
    for (std::size_t a = 1; a < n; ++a) kept.push_back(a);
    const StateLayout before = s->layout();
    s->change_particles(kept, 1);
    const StateLayout& L = s->layout();
    std::vector<Real> y(s->size(), 0);
    for (Field f : L.fields(Species::Gas)) {
      const int c = L.components(Species::Gas, f);
      for (std::size_t i = 0; i < kept.size(); ++i)
        for (int k = 0; k < c; ++k) y[L.offset(f) + c * i + k] = all[before.offset(f) + c * kept[i] + k];
    }
    for (int k = 0; k < 3; ++k) {
      y[L.offset(Species::Sink, Field::Position) + k] = all[before.offset(Field::Position) + k];
      y[L.offset(Species::Sink, Field::Velocity) + k] = all[before.offset(Field::Velocity) + k];
    }
    y[L.offset(Species::Sink, Field::Mass)] = 3 * place.particle_mass;
    return std::pair{s, y};
  };
  auto [s, y] = make();
  const StateLayout layout = s->layout();
  ASSERT_EQ(layout.particles(Species::Sink), 1u);
  std::vector<Real> ydot(y.size());
  ASSERT_EQ(s->rhs(0, y.data(), ydot.data()), 0) << s->last_error();
  EXPECT_GT(Eigen::Map<const Vec<3>>(ydot.data() + layout.offset(Species::Sink, Field::Velocity)).norm(), 0);
  EXPECT_LT(s->potential_energy(), 0);
  compare_paths(layout, "SPMHD gravity + sink 3D", make);
}

}  // namespace
}  // namespace sphark
