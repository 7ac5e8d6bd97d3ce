#pragma once
// Direct summation of kernel-softened self-gravity, O(N^2): the reference the tree is measured
// against. Gather form: each particle sums over every other particle in index order, with the
// pair interaction of kernel_softening.hpp (softened_pair, bitwise symmetric in a and b), so
//   a_a = -G sum_{b != a} m_b f_ab (x_a - x_b),   Phi_a = G m_a phi(0, h_a) + G sum_{b != a} m_b phi_ab
// (PM07 §3). The pair forces m_a m_b f_ab (x_a - x_b) are antisymmetric: momentum is conserved
// to the round-off of the sums. OpenMP over a; no result depends on the thread count.
#include "sphark/gravity/self_gravity.hpp"
#include "sphark/kernels/kernels.hpp"

namespace sphark {

template <class K>
class DirectGravity final : public SelfGravity {
 public:
  explicit DirectGravity(const GravityOptions& options) : G_(options.G) {}
  Real compute(const GravitySources& src, Real* acceleration, Real* potential) override;
  GravitySolver solver() const override { return GravitySolver::Direct; }
  long allocations() const override { return 0; }

 private:
  Real G_;
};

// The sum above for particle a alone (acceleration: 3 values), O(N): the whole solver's inner
// loop, and a reference for a sample of particles where N^2 is too dear (bench/gravity.cpp).
template <class K>
void direct_field_at(const GravitySources& src, std::size_t a, Real G, Real* acceleration, Real* potential);

// (1/2) sum_a m_a Phi_a, summed in index order.
Real potential_energy(const Real* m, const Real* potential, std::size_t n);

}  // namespace sphark
