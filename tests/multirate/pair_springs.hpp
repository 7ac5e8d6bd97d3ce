#pragma once
// A pairwise-antisymmetric toy system for the multirate tests (issue #17, "Conservation").
#include <numeric>
#include <span>
#include <vector>

#include "oscillator_ensemble.hpp"

namespace sphark::test {

// Pairwise antisymmetric springs a_i = sum_j s_i s_j (x_j - x_i) (unit masses): total momentum
// sum_i v_i is invariant; particles 6 and 7 (s = 10) are stiff.
class PairSprings : public OscillatorEnsemble {
 public:
  PairSprings() : OscillatorEnsemble(std::vector<Real>(8, 0.0), 0.0) {}
  Real k(std::size_t i, std::size_t j) const { return s_[i] * s_[j]; }
  Real pair_acceleration(std::size_t i, const Real* y) const {
    Real a = 0;
    for (std::size_t j = 0; j < n(); ++j) a += k(i, j) * (y[j] - y[i]);
    return a;
  }
  int rhs(Real, const Real* y, Real* ydot) override {
    for (std::size_t i = 0; i < n(); ++i) ydot[i] = y[n() + i], ydot[n() + i] = pair_acceleration(i, y);
    return 0;
  }
  int rhs_subset(Real, const Real* y, std::span<const std::size_t> active, Real* ydot) override {
    std::fill(ydot, ydot + size(), 0.0);
    for (std::size_t i : active) ydot[i] = y[n() + i], ydot[n() + i] = pair_acceleration(i, y);
    return 0;
  }
  int particle_stable_dt(Real, const Real*, const Real*, Real* dt) override {
    for (std::size_t i = 0; i < n(); ++i) {
      Real sum = 0;
      for (std::size_t j = 0; j < n(); ++j) sum += j == i ? 0 : k(i, j);
      dt[i] = 1 / std::sqrt(sum);
    }
    return 0;
  }
  static Real momentum(const std::vector<Real>& y) { return std::accumulate(y.begin() + 8, y.end(), 0.0); }

 private:
  const Real s_[8] = {1, 1, 1, 1, 1, 1, 10, 10};
};

inline std::vector<Real> spring_state() {
  std::vector<Real> y(16);
  for (int i = 0; i < 8; ++i) y[i] = 0.3 * std::sin(1.0 + i), y[8 + i] = 0.2 * std::cos(3.0 * i);
  return y;
}

}  // namespace sphark::test
