#pragma once
// An OdeSystem that answers every question with the one it wraps: the base of wrappers that
// change a few answers (the distributed stepper's CollectiveSystem, the GuardedSystem).
#include <string>

#include "sphark/integrate/ode_system.hpp"

namespace sphark {

class ForwardingSystem : public OdeSystem {
 public:
  explicit ForwardingSystem(OdeSystem& inner) : inner_(inner) {}

  std::size_t size() const override { return inner_.size(); }
  const StateLayout* state_layout() const override { return inner_.state_layout(); }
  int rhs(Real t, const Real* y, Real* ydot) override { return inner_.rhs(t, y, ydot); }
  bool has_stiff_diagonal() const override { return inner_.has_stiff_diagonal(); }
  int stiff_diagonal(Real t, const Real* y, Real* c) override { return inner_.stiff_diagonal(t, y, c); }
  std::size_t position_offset() const override { return inner_.position_offset(); }
  std::size_t velocity_offset() const override { return inner_.velocity_offset(); }
  std::size_t position_size() const override { return inner_.position_size(); }
  Real max_stable_dt(Real t, const Real* y, const Real* ydot) override { return inner_.max_stable_dt(t, y, ydot); }
  int num_roots() const override { return inner_.num_roots(); }
  int roots(Real t, const Real* y, Real* g) override { return inner_.roots(t, y, g); }
  std::string last_error() const override { return inner_.last_error(); }
  std::vector<Real> resume_data() const override { return inner_.resume_data(); }
  void resume(std::span<const Real> data) override { inner_.resume(data); }
  std::size_t num_particles() const override { return inner_.num_particles(); }
  std::vector<std::size_t> entry_particles() const override { return inner_.entry_particles(); }
  bool supports_subsets() const override { return inner_.supports_subsets(); }
  int rhs_subset(Real t, const Real* y, std::span<const std::size_t> active, Real* ydot) override {
    return inner_.rhs_subset(t, y, active, ydot);
  }
  int particle_stable_dt(Real t, const Real* y, const Real* ydot, Real* dt) override {
    return inner_.particle_stable_dt(t, y, ydot, dt);
  }
  int active_stable_dt(Real t, const Real* y, const Real* ydot, std::span<const std::size_t> active,
                       Real* dt) override {
    return inner_.active_stable_dt(t, y, ydot, active, dt);
  }

 protected:
  OdeSystem& inner_;
};

}  // namespace sphark
