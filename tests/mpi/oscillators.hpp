#pragma once
// Independent oscillators x'' = -w_k^2 x - kappa x' (global index k) as an OdeSystem over the
// oscillators a rank holds (any subset of 0..N-1, in any order): state [x..., v...]. Serial
// reference = all of them on one rank. Exact solution known for kappa = 0.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "sphark/integrate/ode_system.hpp"

namespace sphark::testing {

inline Real omega(std::int64_t k) { return 1.0 + 0.25 * double(k % 7) + 0.013 * double(k); }
inline Real phase(std::int64_t k) { return 0.7 * double(k); }
inline Real exact_x(std::int64_t k, Real t) { return std::cos(omega(k) * t + phase(k)); }
inline Real exact_v(std::int64_t k, Real t) { return -omega(k) * std::sin(omega(k) * t + phase(k)); }

// Global indices [first, last) of rank r's block of n over p ranks.
inline std::vector<std::int64_t> block(std::int64_t n, int r, int p) {
  std::vector<std::int64_t> ids;
  for (std::int64_t k = n * r / p; k < n * (r + 1) / p; ++k) ids.push_back(k);
  return ids;
}

class Oscillators final : public OdeSystem {
 public:
  explicit Oscillators(std::vector<std::int64_t> ids, Real kappa = 0, bool stiff_damping = false)
      : ids_(std::move(ids)), kappa_(kappa), stiff_(stiff_damping) {}

  void set_ids(std::vector<std::int64_t> ids) { ids_ = std::move(ids); }
  const std::vector<std::int64_t>& ids() const { return ids_; }
  std::size_t count() const { return ids_.size(); }

  // Failure injection: from time t on, rhs() returns `code` (> 0: only on the first such call;
  // < 0: always) or, with code 0, throws.
  void fail_after(Real t, int code) { fail_t_ = t, fail_code_ = code; }
  long rhs_calls() const { return calls_; }

  std::size_t size() const override { return 2 * ids_.size(); }
  int rhs(Real t, const Real* y, Real* ydot) override {
    ++calls_;
    if (t > fail_t_) {
      if (fail_code_ == 0) throw std::runtime_error("oscillator blew up");
      if (fail_code_ < 0 || !failed_once_) {
        failed_once_ = true;
        error_ = "injected failure";
        return fail_code_;
      }
    }
    const std::size_t n = ids_.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Real w = omega(ids_[i]);
      ydot[i] = y[n + i];
      ydot[n + i] = -w * w * y[i] - (stiff_ ? 0.0 : kappa_ * y[n + i]);
    }
    return 0;
  }
  bool has_stiff_diagonal() const override { return stiff_; }
  int stiff_diagonal(Real, const Real*, Real* c) override {  // f_I = -kappa v
    const std::size_t n = ids_.size();
    for (std::size_t i = 0; i < n; ++i) c[i] = 0, c[n + i] = kappa_;
    return 0;
  }
  std::size_t position_offset() const override { return 0; }
  std::size_t velocity_offset() const override { return ids_.size(); }
  std::size_t position_size() const override { return ids_.size(); }
  Real max_stable_dt(Real, const Real*, const Real*) override {
    Real w = 0;
    for (auto k : ids_) w = std::max(w, omega(k));
    return w > 0 ? 0.5 / w : std::numeric_limits<Real>::infinity();
  }
  // g0 = min_i x_i + 1.05 - 0.1 t (reduced by min), g1 = max_i x_i - 1.1 + 0.08 t (max),
  // g2 = sum_i x_i^2 - 0.2 t N (sum; N = total number of oscillators).
  int num_roots() const override { return roots_ ? 3 : 0; }
  void enable_roots(Real total) { roots_ = true, total_ = total; }
  int roots(Real t, const Real* y, Real* g) override {
    const std::size_t n = ids_.size();
    Real lo = std::numeric_limits<Real>::infinity(), hi = -lo, e = 0;
    for (std::size_t i = 0; i < n; ++i) lo = std::min(lo, y[i]), hi = std::max(hi, y[i]), e += y[i] * y[i];
    g[0] = lo + 1.05 - 0.1 * t;
    g[1] = hi - 1.1 + 0.08 * t;
    g[2] = e - (total_share_ ? 0.2 * t * total_ : 0.0);
    return 0;
  }
  // In a distributed run the sum root's constant term must be counted once: on one rank only.
  void set_total_share(bool share) { total_share_ = share; }
  std::string last_error() const override { return error_; }

  // Initial state of the held oscillators (exact solution at t = 0).
  std::vector<Real> initial_state() const {
    const std::size_t n = ids_.size();
    std::vector<Real> y(2 * n);
    for (std::size_t i = 0; i < n; ++i) y[i] = exact_x(ids_[i], 0), y[n + i] = exact_v(ids_[i], 0);
    return y;
  }

 private:
  std::vector<std::int64_t> ids_;
  Real kappa_;
  bool stiff_;
  bool roots_ = false, total_share_ = true;
  Real total_ = 0;
  Real fail_t_ = std::numeric_limits<Real>::infinity();
  int fail_code_ = 0;
  bool failed_once_ = false;
  long calls_ = 0;
  std::string error_;
};

// Entry (x or v) of oscillator k in a state over `ids` (or -1 if k is not held).
inline std::ptrdiff_t slot(const std::vector<std::int64_t>& ids, std::int64_t k) {
  const auto it = std::find(ids.begin(), ids.end(), k);
  return it == ids.end() ? -1 : it - ids.begin();
}

}  // namespace sphark::testing
