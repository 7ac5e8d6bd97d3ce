#pragma once
// The two-time-scale test problem of issue #17 (sphark/study/oscillator_model.hpp), its calls
// counted: full_calls, subset_calls, and with record_calls every rhs_subset call's (t, active).
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "sphark/study/oscillator_model.hpp"

namespace sphark::test {

class OscillatorEnsemble : public OscillatorModel {
 public:
  using OscillatorModel::OscillatorModel;
  int rhs(Real t, const Real* y, Real* ydot) override {
    ++full_calls;
    return OscillatorModel::rhs(t, y, ydot);
  }
  int rhs_subset(Real t, const Real* y, std::span<const std::size_t> active, Real* ydot) override {
    ++subset_calls;
    if (record_calls) calls.push_back({t, std::vector<std::size_t>(active.begin(), active.end())});
    return OscillatorModel::rhs_subset(t, y, active, ydot);
  }

  long full_calls = 0, subset_calls = 0;
  struct Call {
    Real t;
    std::vector<std::size_t> active;
  };
  bool record_calls = false;
  std::vector<Call> calls;  // every rhs_subset call when record_calls
};

// The largest |a_k - b_k| over every entry.
inline Real max_error(const std::vector<Real>& a, const std::vector<Real>& b) {
  Real e = 0;
  for (std::size_t k = 0; k < a.size(); ++k) e = std::max(e, std::abs(a[k] - b[k]));
  return e;
}

}  // namespace sphark::test
