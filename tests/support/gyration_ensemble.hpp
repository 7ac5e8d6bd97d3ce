#pragma once
// A velocity-dependent test system for the leapfrogs' corrector iterations (tests/integrate,
// tests/multirate): particles gyrating in the plane, a_i = omega_i (v_y, -v_x), which keeps |v_i|.
#include <algorithm>
#include <span>
#include <vector>

#include "sphark/integrate/ode_system.hpp"

namespace sphark::test {

// Particle i owns x (entries 2i, 2i+1) and v (2N + 2i, 2N + 2i + 1); its stable step is
// 0.5 / omega_i, so that omega_i dt = 0.5 on its own level.
class GyrationEnsemble : public OdeSystem {
 public:
  explicit GyrationEnsemble(std::vector<Real> omega) : w_(std::move(omega)) {}
  std::size_t n() const { return w_.size(); }
  std::size_t size() const override { return 4 * n(); }
  std::size_t num_particles() const override { return n(); }
  std::size_t position_offset() const override { return 0; }
  std::size_t velocity_offset() const override { return 2 * n(); }
  std::size_t position_size() const override { return 2 * n(); }
  bool supports_subsets() const override { return true; }
  std::vector<std::size_t> entry_particles() const override {
    std::vector<std::size_t> owner(size());
    for (std::size_t k = 0; k < size(); ++k) owner[k] = (k % (2 * n())) / 2;
    return owner;
  }
  int rhs(Real t, const Real* y, Real* ydot) override {
    std::vector<std::size_t> all(n());
    for (std::size_t i = 0; i < n(); ++i) all[i] = i;
    return rhs_subset(t, y, all, ydot);
  }
  int rhs_subset(Real, const Real* y, std::span<const std::size_t> active, Real* ydot) override {
    std::fill(ydot, ydot + size(), 0.0);
    const std::size_t v = 2 * n();
    for (std::size_t i : active) {
      ydot[2 * i] = y[v + 2 * i], ydot[2 * i + 1] = y[v + 2 * i + 1];
      ydot[v + 2 * i] = w_[i] * y[v + 2 * i + 1], ydot[v + 2 * i + 1] = -w_[i] * y[v + 2 * i];
    }
    return 0;
  }
  int particle_stable_dt(Real, const Real*, const Real*, Real* dt) override {
    for (std::size_t i = 0; i < n(); ++i) dt[i] = 0.5 / w_[i];
    return 0;
  }
  Real max_stable_dt(Real, const Real*, const Real*) override { return 0.5 / *std::max_element(w_.begin(), w_.end()); }

 private:
  std::vector<Real> w_;
};

}  // namespace sphark::test
