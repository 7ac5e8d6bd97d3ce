#include "sphark/derivatives1d/bvp1d.hpp"

#include <Eigen/SparseLU>
#include <stdexcept>

namespace sphark::d1 {

Eigen::VectorXd solve_dirichlet(const SparseMatrix& L, const Particles1D& p, const Eigen::VectorXd& g,
                                Real u_left, Real u_right) {
  const Index n = p.size();
  std::vector<Eigen::Triplet<Real>> t;
  t.reserve(L.nonZeros() + 2);
  for (Index col = 0; col < L.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(L, col); it; ++it)
      if (!p.on_boundary(it.row())) t.emplace_back(it.row(), it.col(), it.value());
  t.emplace_back(p.left(), p.left(), 1.0);  // seed 001 (5.18): boundary particles carry f(0), f(1)
  t.emplace_back(p.right(), p.right(), 1.0);
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  Eigen::VectorXd b = g;
  b[p.left()] = u_left;
  b[p.right()] = u_right;
  Eigen::SparseLU<SparseMatrix> lu;
  lu.compute(A);
  if (lu.info() != Eigen::Success) throw std::runtime_error("solve_dirichlet: sparse LU failed (singular operator)");
  return lu.solve(b);
}

}  // namespace sphark::d1
