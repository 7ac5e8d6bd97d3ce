#pragma once
// The multirate model problem of issue #17: an ensemble of oscillators x_i'' = -w_i^2 x_i
// + kappa sum_j (x_j - x_i) (all-pairs springs, pairwise antisymmetric), e.g. frequencies w_i of
// 1 and 100. y = (x_0 .. x_{N-1}, v_0 .. v_{N-1}); particle i owns entries i and N + i. Linear:
// x'' = -K x with K = diag(w^2) + kappa (N I - 1 1^T), solved exactly by K's eigenmodes. Used by
// the multirate tests (tests/multirate/) and their work-precision bench
// (bench/multirate_oscillators.cpp). Each evaluation of a particle costs O(N) (all pairs).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "sphark/integrate/ode_system.hpp"

namespace sphark {

class OscillatorModel : public OdeSystem {
 public:
  OscillatorModel(std::vector<Real> omega, Real kappa) : w_(std::move(omega)), kappa_(kappa) { decompose(); }
  // Particles leaving and coming back (a stepper's remove_active / undo_removals).
  void remove_particle(std::size_t i) {
    w_.erase(w_.begin() + static_cast<std::ptrdiff_t>(i));
    decompose();
  }
  void insert_particle(std::size_t i, Real omega) {
    w_.insert(w_.begin() + static_cast<std::ptrdiff_t>(i), omega);
    decompose();
  }
  std::size_t n() const { return w_.size(); }
  std::size_t size() const override { return 2 * n(); }
  std::size_t num_particles() const override { return n(); }
  std::size_t position_offset() const override { return 0; }
  std::size_t velocity_offset() const override { return n(); }
  std::size_t position_size() const override { return n(); }
  bool supports_subsets() const override { return true; }
  std::vector<std::size_t> entry_particles() const override {
    std::vector<std::size_t> owner(size());
    for (std::size_t k = 0; k < size(); ++k) owner[k] = k % n();
    return owner;
  }

  Real acceleration(std::size_t i, const Real* y) const {
    Real a = -w_[i] * w_[i] * y[i];
    for (std::size_t j = 0; j < n(); ++j) a += kappa_ * (y[j] - y[i]);
    return a;
  }
  int rhs(Real, const Real* y, Real* ydot) override {
    for (std::size_t i = 0; i < n(); ++i) {
      ydot[i] = y[n() + i];
      ydot[n() + i] = acceleration(i, y);
    }
    return 0;
  }
  int rhs_subset(Real, const Real* y, std::span<const std::size_t> active, Real* ydot) override {
    std::fill(ydot, ydot + size(), 0.0);
    for (std::size_t i : active) {
      ydot[i] = y[n() + i];
      ydot[n() + i] = acceleration(i, y);
    }
    return 0;
  }
  // The explicit stability limit of an oscillator, scaled: 1 / w_i.
  int particle_stable_dt(Real, const Real*, const Real*, Real* dt) override {
    for (std::size_t i = 0; i < n(); ++i) dt[i] = 1 / w_[i];
    return 0;
  }
  Real max_stable_dt(Real, const Real*, const Real*) override {
    return 1 / *std::max_element(w_.begin(), w_.end());
  }

  // The exact state at t from y0.
  std::vector<Real> exact(const std::vector<Real>& y0, Real t) const {
    const int m = static_cast<int>(n());
    const Eigen::MatrixXd& q = eig_.eigenvectors();
    const Eigen::VectorXd a = q.transpose() * Eigen::Map<const Eigen::VectorXd>(y0.data(), m);
    const Eigen::VectorXd b = q.transpose() * Eigen::Map<const Eigen::VectorXd>(y0.data() + m, m);
    Eigen::VectorXd x(m), v(m);
    for (int k = 0; k < m; ++k) {
      const Real s = std::sqrt(eig_.eigenvalues()[k]);
      x[k] = a[k] * std::cos(s * t) + b[k] / s * std::sin(s * t);
      v[k] = -a[k] * s * std::sin(s * t) + b[k] * std::cos(s * t);
    }
    x = q * x;
    v = q * v;
    std::vector<Real> y(2 * n());
    for (int i = 0; i < m; ++i) y[i] = x[i], y[m + i] = v[i];
    return y;
  }
  // A state in the span of the modes whose frequency is below `cut` (the "slow manifold":
  // the fast modes are not excited), from positions x and velocities v.
  std::vector<Real> project_below(const std::vector<Real>& y, Real cut) const {
    const int m = static_cast<int>(n());
    const Eigen::MatrixXd& q = eig_.eigenvectors();
    Eigen::VectorXd a = q.transpose() * Eigen::Map<const Eigen::VectorXd>(y.data(), m);
    Eigen::VectorXd b = q.transpose() * Eigen::Map<const Eigen::VectorXd>(y.data() + m, m);
    for (int k = 0; k < m; ++k)
      if (std::sqrt(eig_.eigenvalues()[k]) >= cut) a[k] = b[k] = 0;
    const Eigen::VectorXd x = q * a, v = q * b;
    std::vector<Real> out(2 * n());
    for (int i = 0; i < m; ++i) out[i] = x[i], out[m + i] = v[i];
    return out;
  }

 private:
  void decompose() {
    const int n = static_cast<int>(w_.size());
    Eigen::MatrixXd k = Eigen::MatrixXd::Constant(n, n, -kappa_);
    for (int i = 0; i < n; ++i) k(i, i) = w_[i] * w_[i] + kappa_ * (n - 1);
    eig_.compute(k);
  }

  std::vector<Real> w_;
  Real kappa_;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig_;
};

// The separated-scales case of the work-precision bench (bench/multirate_oscillators.cpp): `slow`
// frequencies evenly in [1, 2) and `fast` ones at fast_omega.
inline std::vector<Real> separated_frequencies(int slow, int fast, Real fast_omega) {
  std::vector<Real> w;
  for (int i = 0; i < slow; ++i) w.push_back(1 + static_cast<Real>(i) / slow);
  for (int i = 0; i < fast; ++i) w.push_back(fast_omega);
  return w;
}

// Every mode excited: x_i = cos(1 + i), v_i = sin(2 i).
inline std::vector<Real> excited_state(std::size_t n) {
  std::vector<Real> y(2 * n);
  for (std::size_t i = 0; i < n; ++i) y[i] = std::cos(1.0 + i), y[n + i] = std::sin(2.0 * i);
  return y;
}

// max_i |x_i - x_i*| + |v_i - v_i*| / w_i: each oscillator's error in its own amplitude units.
inline Real oscillator_error(const std::vector<Real>& y, const std::vector<Real>& exact, const std::vector<Real>& w) {
  const std::size_t n = w.size();
  Real e = 0;
  for (std::size_t i = 0; i < n; ++i)
    e = std::max(e, std::abs(y[i] - exact[i]) + std::abs(y[n + i] - exact[n + i]) / w[i]);
  return e;
}

}  // namespace sphark
