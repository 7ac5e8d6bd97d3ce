#include "sphark/diagnostics/spmhd_diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sphark {

namespace {
// The sink particles' kinetic energy and momentum (their potential energy is in the scheme's).
void add_sinks(const StateLayout& L, const Real* y, SpmhdDiagnostics& d) {
  const std::size_t ns = L.particles(Species::Sink);
  if (ns == 0) return;
  const Real* v = y + L.offset(Species::Sink, Field::Velocity);
  const Real* m = y + L.offset(Species::Sink, Field::Mass);
  for (std::size_t k = 0; k < ns; ++k) {
    Real v2 = 0;
    for (int c = 0; c < 3; ++c) {
      v2 += v[3 * k + c] * v[3 * k + c];
      d.momentum[c] += m[k] * v[3 * k + c];
    }
    d.kinetic_energy += 0.5 * m[k] * v2;
  }
}
}  // namespace

template <int D, class K>
SpmhdDiagnostics spmhd_diagnostics(SpmhdScheme<D, K>& s, Real t, const Real* y) {
  SpmhdDiagnostics d;
  if (s.evaluate(t, y) != 0) {
    d.mean_h_divb_over_b = d.max_h_divb_over_b = std::nan("");
    return d;
  }
  const StateLayout& L = s.layout();
  const std::size_t n = s.particles();
  const auto& m = s.masses();
  const auto& B = s.magnetic_field();
  const Real* v = L.has(Field::Velocity) ? y + L.offset(Field::Velocity) : nullptr;
  const Real* u = L.has(Field::InternalEnergy) ? y + L.offset(Field::InternalEnergy) : nullptr;
  const Real* psi = L.has(Field::Psi) ? y + L.offset(Field::Psi) : nullptr;
  const Real ch = s.cleaning_speed();
  std::size_t counted = 0;
  for (std::size_t a = 0; a < n; ++a) {
    const Real rho = s.rho()[a];
    const Real b2 = B[3 * a] * B[3 * a] + B[3 * a + 1] * B[3 * a + 1] + B[3 * a + 2] * B[3 * a + 2];
    d.max_h_divb = std::max(d.max_h_divb, s.h()[a] * std::abs(s.div_b()[a]));
    if (b2 > 0) {
      const Real e = s.h()[a] * std::abs(s.div_b()[a]) / std::sqrt(b2);
      d.mean_h_divb_over_b += e;
      d.max_h_divb_over_b = std::max(d.max_h_divb_over_b, e);
      ++counted;
    }
    d.magnetic_energy += m[a] * b2 / (2 * rho);
    if (v) {
      Real v2 = 0;
      for (int k = 0; k < D; ++k) {
        v2 += v[D * a + k] * v[D * a + k];
        d.momentum[k] += m[a] * v[D * a + k];
      }
      d.kinetic_energy += 0.5 * m[a] * v2;
    }
    if (u) d.thermal_energy += m[a] * u[a];
    else if (const BarotropicEos* eos = s.barotropic_eos()) d.thermal_energy += m[a] * eos->specific_energy(rho);
    if (psi && s.options().local_ch) d.psi_energy += m[a] * psi[a] * psi[a] / (2 * rho);  // state psi / c_h,a
    else if (psi && ch > 0) d.psi_energy += m[a] * psi[a] * psi[a] / (2 * rho * ch * ch);
  }
  if (s.distributed()) {  // every rank's sums and maxima (collective)
    Real sums[6] = {d.mean_h_divb_over_b, static_cast<Real>(counted), d.magnetic_energy, d.kinetic_energy,
                    d.thermal_energy, d.psi_energy};
    Real maxima[2] = {d.max_h_divb, d.max_h_divb_over_b};
    s.communicator().allreduce(sums, 6, ReduceOp::Sum);
    s.communicator().allreduce(d.momentum.data(), 3, ReduceOp::Sum);
    s.communicator().allreduce(maxima, 2, ReduceOp::Max);
    d.mean_h_divb_over_b = sums[0], d.magnetic_energy = sums[2], d.kinetic_energy = sums[3];
    d.thermal_energy = sums[4], d.psi_energy = sums[5];
    d.max_h_divb = maxima[0], d.max_h_divb_over_b = maxima[1];
    counted = static_cast<std::size_t>(sums[1]);
  }
  if (counted > 0) d.mean_h_divb_over_b /= static_cast<Real>(counted);
  add_sinks(L, y, d);
  d.potential_energy = s.potential_energy();
  d.total_energy = d.kinetic_energy + d.magnetic_energy + d.thermal_energy + d.psi_energy + d.potential_energy;
  d.cleaning_speed = ch;
  return d;
}

namespace {
// The gas values of an array followed by NaN for each sink (gas-only quantities).
void pad_for_sinks(std::vector<Real>& a, std::size_t sinks, int components) {
  a.resize(a.size() + sinks * static_cast<std::size_t>(components), std::nan(""));
}
}  // namespace

template <int D, class K>
ParticleFrame SpmhdFrame::build(SpmhdScheme<D, K>& s, Real t, const Real* y, const PeriodicBox<D>* box) {
  if (s.evaluate(t, y) != 0) throw std::runtime_error("SPMHD frame at t=" + std::to_string(t) + ": " + s.last_error());
  const std::size_t n = s.particles();
  const StateLayout& L = s.layout();
  const std::size_t ns = L.particles(Species::Sink);
  const auto& B = s.magnetic_field();
  magnetic_pressure_.resize(n);
  error_.resize(n);
  for (std::size_t a = 0; a < n; ++a) {
    const Real b2 = B[3 * a] * B[3 * a] + B[3 * a + 1] * B[3 * a + 1] + B[3 * a + 2] * B[3 * a + 2];
    magnetic_pressure_[a] = 0.5 * b2;
    error_[a] = b2 > 0 ? s.h()[a] * std::abs(s.div_b()[a]) / std::sqrt(b2) : 0.0;
  }
  const Real* x = L.has(Field::Position) ? y + L.offset(Field::Position) : s.positions().data();
  positions_.assign(x, x + D * n);
  if (ns > 0) positions_.insert(positions_.end(), y + L.offset(Species::Sink, Field::Position),
                                y + L.offset(Species::Sink, Field::Position) + D * ns);
  if (box) box->wrap_all(positions_.data(), n + ns, positions_.data());
  density_ = s.rho();
  div_b_ = s.div_b();
  field_ = B;
  h_ = s.h();
  for (std::vector<Real>* a : {&density_, &magnetic_pressure_, &div_b_, &error_, &h_}) pad_for_sinks(*a, ns, 1);
  pad_for_sinks(field_, ns, 3);
  ParticleFrame f;
  f.dim = D;
  f.count = n + ns;
  f.positions = positions_.data();
  f.arrays = {{"density", density_.data(), 1}, {"magnetic_pressure", magnetic_pressure_.data(), 1},
              {"div_B", div_b_.data(), 1}, {"h_divB_over_B", error_.data(), 1}};
  if (L.has(Field::Velocity)) {
    pressure_ = s.pressure();
    pad_for_sinks(pressure_, ns, 1);
    f.arrays.push_back({"pressure", pressure_.data(), 1});
  }
  f.arrays.push_back({"magnetic_field", field_.data(), 3});
  if (L.has(Field::Velocity)) {
    const Real* v = y + L.offset(Field::Velocity);
    velocity_.assign(v, v + D * n);
    if (ns > 0) velocity_.insert(velocity_.end(), y + L.offset(Species::Sink, Field::Velocity),
                                 y + L.offset(Species::Sink, Field::Velocity) + D * ns);
    f.arrays.push_back({"velocity", velocity_.data(), D});
  }
  if (L.has(Field::Psi)) {
    const Real* psi = y + L.offset(Field::Psi);
    psi_.assign(psi, psi + n);
    pad_for_sinks(psi_, ns, 1);
    f.arrays.push_back({"psi", psi_.data(), 1});
  }
  f.arrays.push_back({"h", h_.data(), 1});
  if (L.has(Species::Sink)) add_species_arrays(s.masses(), y + L.offset(Species::Sink, Field::Mass), ns, f);
  return f;
}

// With a sink species: "species" (0 gas, 1 sink) and "mass" (the particle's or the sink's).
void SpmhdFrame::add_species_arrays(const std::vector<Real>& gas_masses, const Real* sink_masses, std::size_t sinks,
                                    ParticleFrame& f) {
  const std::size_t n = gas_masses.size();
  species_.assign(n + sinks, 1.0);
  std::fill_n(species_.begin(), n, 0.0);
  mass_ = gas_masses;
  mass_.insert(mass_.end(), sink_masses, sink_masses + sinks);
  f.arrays.push_back({"species", species_.data(), 1});
  f.arrays.push_back({"mass", mass_.data(), 1});
}

template SpmhdDiagnostics spmhd_diagnostics(SpmhdScheme<2, CubicSpline<2>>&, Real, const Real*);
template SpmhdDiagnostics spmhd_diagnostics(SpmhdScheme<3, CubicSpline<3>>&, Real, const Real*);
template ParticleFrame SpmhdFrame::build(SpmhdScheme<2, CubicSpline<2>>&, Real, const Real*, const PeriodicBox<2>*);
template ParticleFrame SpmhdFrame::build(SpmhdScheme<3, CubicSpline<3>>&, Real, const Real*, const PeriodicBox<3>*);

}  // namespace sphark
