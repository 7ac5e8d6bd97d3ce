#pragma once
// SPH derivative operators near boundaries in 1D (seed 001), each assembled as a sparse matrix
// L acting on the vector of particle values f_i:  <f''>_i = (L f)_i.
//
// Equations as implemented (corrected where the printed formula does not reproduce the paper's
// Tables 1-3; derivation in docs/second_derivative_1d.md):
//   CSPM  f'   seed 001 (3.5)-(3.6), discrete form under (5.17), with W'_ij (printed: W_ij)
//   CSPM  f''  seed 001 (4.7) / (5.15)
//   BIM   f''  seed 001 (4.9) / (5.16), with the boundary terms inside the factor 2/gamma_i
//   ICSPM f''  seed 001 (4.13) / (5.17), kappa_i = 1 - ... (printed: 1 + ...), eq. (4.14)
// W'_ij is the derivative with respect to x_i (kernel1d.hpp).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "sphark/derivatives1d/particles1d.hpp"

namespace sphark::d1 {

using SparseMatrix = Eigen::SparseMatrix<Real>;  // column-major, what SparseLU wants

// Neighbours within the kernel support (|x_j - x_i| < 2h), self included, in CSR form.
struct Neighbours1D {
  std::vector<Index> offset;  // size N + 1
  std::vector<Index> index;   // neighbours of i: index[offset[i] .. offset[i+1])
  Index count(Index i) const { return offset[i + 1] - offset[i]; }
};
Neighbours1D find_neighbours(const Eigen::VectorXd& x, Real radius);

// Discrete moments of seed 001 §V (sums over j in N_i, weights |Omega_j|).
struct Moments1D {
  Eigen::VectorXd gamma;        // gamma_i   = sum W_ij |Omega_j|                       (4.10)
  Eigen::VectorXd gamma_tilde;  // gamma~_i  = sum (x_j - x_i) W'_ij |Omega_j|          (3.6)
  Eigen::VectorXd gamma_star;   // gamma*_i  = sum (x_j - x_i)^2 / 2 W_ij |Omega_j|     (4.8)
  Eigen::VectorXd m1;           //             sum (x_j - x_i) W_ij |Omega_j|
  Eigen::VectorXd m2_prime;     //             sum (x_j - x_i)^2 / 2 W'_ij |Omega_j|
  Eigen::VectorXd kappa;        // kappa_i = 1 - m2'_i m1_i / (gamma~_i gamma*_i)     (4.14), sign corrected
};
Moments1D moments(const Particles1D& p, Real h);

// seed 001 (3.5)-(3.6): <f'>_i = 1/gamma~_i sum (f_j - f_i) W'_ij |Omega_j|
SparseMatrix cspm_first_derivative(const Particles1D& p, Real h);

// seed 001 (4.7)/(5.15): <f''>_i = [sum (f_j - f_i) W_ij |Omega_j| - <f'>_i m1_i] / gamma*_i
SparseMatrix cspm_second_derivative(const Particles1D& p, Real h);

// seed 001 (4.13)/(5.17): <f''>_ICSPM = <f''>_CSPM / kappa_i
SparseMatrix icspm_second_derivative(const Particles1D& p, Real h);

// seed 001 (4.9)/(5.16), corrected:
//   <f''>_i = 2/gamma_i [ sum (f_j - f_i)/(x_j - x_i) W'_ij |Omega_j|
//                         + (f_i - f_r)/(x_i - x_r) W_ir - (f_i - f_l)/(x_i - x_l) W_il ]
// with f_l, f_r the values of the particles on x_l, x_r. The rows of those two boundary particles
// are 0/0 in the paper and are left empty (all zero): the paper neglects them.
SparseMatrix bim_second_derivative(const Particles1D& p, Real h);

enum class Method { Cspm, Bim, Icspm };
const char* method_name(Method m);
SparseMatrix second_derivative(Method m, const Particles1D& p, Real h);
// The particles at which a method's <f''>_i is defined (BIM: not on the boundary).
bool row_defined(Method m, const Particles1D& p, Index i);

}  // namespace sphark::d1
