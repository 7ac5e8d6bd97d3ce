#pragma once
// Dirichlet boundary-value problem with an SPH second-derivative operator (seed 001, eq. (5.18)):
//   (L u)_i = g_i  for every particle not on the boundary,
//   u_l = u_left, u_r = u_right  on the two boundary particles (rows replaced by identity rows).
// Solved with Eigen's sparse LU.
#include <Eigen/Core>

#include "sphark/derivatives1d/operators1d.hpp"

namespace sphark::d1 {

// Throws std::runtime_error if the system is singular.
Eigen::VectorXd solve_dirichlet(const SparseMatrix& L, const Particles1D& p, const Eigen::VectorXd& g,
                                Real u_left, Real u_right);

}  // namespace sphark::d1
