#pragma once
// Small ODE systems with exact solutions for the stepper tests.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphark/integrate/ode_system.hpp"
#include "sphark/integrate/stepper.hpp"

namespace sphark::test {

// Kepler problem q'' = -q / |q|^3, eccentricity e, period 2 pi: y = (q1, q2, p1, p2).
// Exact solution through Kepler's equation E - e sin E = t.
class Kepler : public OdeSystem {
 public:
  explicit Kepler(Real e) : e_(e) {}
  std::size_t size() const override { return 4; }
  int rhs(Real, const Real* y, Real* ydot) override {
    const Real r = std::hypot(y[0], y[1]), r3 = r * r * r;
    ydot[0] = y[2];
    ydot[1] = y[3];
    ydot[2] = -y[0] / r3;
    ydot[3] = -y[1] / r3;
    return 0;
  }
  std::size_t position_offset() const override { return 0; }
  std::size_t velocity_offset() const override { return 2; }
  std::size_t position_size() const override { return 2; }
  std::vector<Real> exact(Real t) const {
    Real E = t;
    for (int i = 0; i < 50; ++i) E -= (E - e_ * std::sin(E) - t) / (1 - e_ * std::cos(E));
    const Real s = std::sqrt(1 - e_ * e_), d = 1 - e_ * std::cos(E);
    return {std::cos(E) - e_, s * std::sin(E), -std::sin(E) / d, s * std::cos(E) / d};
  }

 private:
  Real e_;
};

// Damped oscillator with an extra evolved field (like an SPH energy equation):
// x' = v, v' = -x - g v, e' = -g v^2, so e = (x^2 + v^2 - 1) / 2 for y0 = (1, 0, 0).
class DampedWithEnergy : public OdeSystem {
 public:
  explicit DampedWithEnergy(Real g) : g_(g) {}
  std::size_t size() const override { return 3; }
  int rhs(Real, const Real* y, Real* ydot) override {
    ydot[0] = y[1];
    ydot[1] = -y[0] - g_ * y[1];
    ydot[2] = -g_ * y[1] * y[1];
    return 0;
  }
  std::size_t position_offset() const override { return 0; }
  std::size_t velocity_offset() const override { return 1; }
  std::size_t position_size() const override { return 1; }
  std::vector<Real> exact(Real t) const {
    const Real w = std::sqrt(1 - g_ * g_ / 4), a = std::exp(-g_ * t / 2);
    const Real x = a * (std::cos(w * t) + g_ / (2 * w) * std::sin(w * t));
    const Real v = -a * std::sin(w * t) / w;
    return {x, v, 0.5 * (x * x + v * v - 1)};
  }

 private:
  Real g_;
};

// x'' = -x as y = (x, v): x = cos t, v = -sin t for y0 = (1, 0).
class Oscillator : public OdeSystem {
 public:
  std::size_t size() const override { return 2; }
  int rhs(Real, const Real* y, Real* ydot) override {
    ydot[0] = y[1];
    ydot[1] = -y[0];
    return 0;
  }
  std::size_t position_offset() const override { return 0; }
  std::size_t velocity_offset() const override { return 1; }
  std::size_t position_size() const override { return 1; }
};

// x'' = -1 from x = 1 at rest; root g = x at t = sqrt(2).
class FallingBall : public Oscillator {
 public:
  int rhs(Real, const Real* y, Real* ydot) override {
    ydot[0] = y[1];
    ydot[1] = -1;
    return 0;
  }
  int num_roots() const override { return 1; }
  int roots(Real, const Real* y, Real* g) noexcept override {
    g[0] = y[0];
    return 0;
  }
};

// y_k' = -c_k (y_k - cos t) - sin t: y_k = cos t for y_k(0) = 1. Stiff part -c_k y_k.
class StiffRelaxation : public OdeSystem {
 public:
  explicit StiffRelaxation(std::vector<Real> c, bool forcing = true)
      : c_(std::move(c)), forcing_(forcing) {}
  std::size_t size() const override { return c_.size(); }
  int rhs(Real t, const Real* y, Real* ydot) override {
    for (std::size_t k = 0; k < c_.size(); ++k)
      ydot[k] = -c_[k] * y[k] + (forcing_ ? c_[k] * std::cos(t) - std::sin(t) : 0.0);
    return 0;
  }
  bool has_stiff_diagonal() const override { return true; }
  int stiff_diagonal(Real, const Real*, Real* c) override {
    for (std::size_t k = 0; k < c_.size(); ++k) c[k] = c_[k];
    return 0;
  }

 private:
  std::vector<Real> c_;
  bool forcing_;
};

// Oscillator driving a stiffly damped scalar (like the cleaning field psi):
// x'' = -x, psi' = x - c psi. With x = cos t, psi0 = c / (1 + c^2):
// psi = (c cos t + sin t) / (1 + c^2). Stiff part: -c psi.
class DampedOscillator : public Oscillator {
 public:
  explicit DampedOscillator(Real c) : c_(c) {}
  std::size_t size() const override { return 3; }
  int rhs(Real t, const Real* y, Real* ydot) override {
    ydot[2] = y[0] - c_ * y[2];
    return Oscillator::rhs(t, y, ydot);
  }
  bool has_stiff_diagonal() const override { return true; }
  int stiff_diagonal(Real, const Real*, Real* c) override {
    c[0] = c[1] = 0;
    c[2] = c_;
    return 0;
  }
  Real psi(Real t) const { return (c_ * std::cos(t) + std::sin(t)) / (1 + c_ * c_); }

 private:
  Real c_;
};

// Oscillator whose RHS refuses (recoverable, +1) to be evaluated more than `jump` ahead of the
// latest time it accepted: like an SPH scheme whose neighbour list is valid only within a skin.
class JumpLimitedOscillator : public Oscillator {
 public:
  explicit JumpLimitedOscillator(Real jump) : jump_(jump) {}
  int rhs(Real t, const Real* y, Real* ydot) override {
    if (t > t_ok_ + jump_) return 1;
    t_ok_ = std::max(t_ok_, t);
    return Oscillator::rhs(t, y, ydot);
  }
  std::string last_error() const override { return "stage jumped beyond the skin"; }
  bool has_stiff_diagonal() const override { return true; }
  int stiff_diagonal(Real, const Real*, Real* c) override {
    c[0] = c[1] = 0;
    return 0;
  }

 private:
  Real jump_;
  Real t_ok_ = 0;
};

// Oscillator whose RHS fails fatally (-1) after t_fail; last_error() may itself throw.
class FailingOscillator : public JumpLimitedOscillator {
 public:
  FailingOscillator(Real t_fail, bool throwing_reason)
      : JumpLimitedOscillator(1e300), t_fail_(t_fail), throwing_(throwing_reason) {}
  int rhs(Real t, const Real* y, Real* ydot) override {
    return t > t_fail_ ? -1 : Oscillator::rhs(t, y, ydot);
  }
  std::string last_error() const override {
    if (throwing_) throw std::runtime_error("last_error exploded");
    return "density became negative";
  }

 private:
  Real t_fail_;
  bool throwing_;
};

inline StepperOptions options(const std::string& method, Real rtol = 1e-6, Real fixed_dt = 0) {
  StepperOptions o;
  o.method = method;
  o.rtol = rtol;
  o.fixed_dt = fixed_dt;
  return o;
}

}  // namespace sphark::test
