#pragma once
// Node density (seed 004, eq. 3) and particle relaxation to a uniform node density.
//
// The paper relaxes its particles with ALARIC. Here: gradient descent on the node-density
// fluctuation ("particle shifting"), in a box that is periodic along every axis:
//   x_i <- x_i - beta * dx^2 * grad n_i / <n>,   grad n_i = sum_j dW/dr (x_i - x_j)/r_ij,
// with the displacement clamped to 0.2 dx (dx = (V/N)^(1/D)), until std(n)/<n> <= tolerance.
// A fully periodic box has no wall, so the relaxed set is uniform up to any wall later cut into
// it: the static tests then compare ghost maps without a relaxation that already favours one map
// (relaxing against mirror or density-preserving ghosts would build that map into the set).
// Kernel: Wendland C4 with support H = 2h (the paper's kernel, seed 004 §2).
// Setting the environment variable SPHARK_RELAX_TRACE prints the progress to stderr.
#include <cstddef>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/neighbours/neighbour_search.hpp"

namespace sphark {

// n_i = sum_j W(|x_i - x_j|, h) over the built lists plus the self term W(0, h); the search must
// have been built on x (n points) with radius >= 2h. Wendland C4.
template <int D>
void node_density(const NeighbourSearch<D>& search, const Real* x, std::size_t n, Real h, Real* out);

struct RelaxOptions {
  Real h_over_dx = 1.3;      // h = h_over_dx * dx
  int max_iterations = 2000;
  Real tolerance = 5e-3;     // target std(n)/<n>
  Real beta = 0.5;
};

struct RelaxReport {
  int iterations = 0;
  Real mean = 0;         // <n>
  Real rel_std = 0;      // std(n)/<n>
  Real max_rel_dev = 0;  // max |n/<n> - 1|
  Real h = 0;
  Real dx = 0;
};

// n uniformly random points in the box (fixed seed: deterministic).
template <int D>
std::vector<Real> random_points(std::size_t n, const PeriodicBox<D>& box, unsigned seed);

// About n points on a cubic lattice filling the box, each displaced uniformly by up to
// +-jitter/2 lattice spacings per axis (fixed seed): a start without close pairs.
template <int D>
std::vector<Real> jittered_lattice(std::size_t n, const PeriodicBox<D>& box, Real jitter, unsigned seed);

// Relaxes x (D x n, modified in place) in the fully periodic box. Throws StopRequested
// (run/signals.hpp) at the next iteration after SIGINT/SIGTERM.
template <int D>
RelaxReport relax_uniform(std::vector<Real>& x, const PeriodicBox<D>& box, const RelaxOptions& opt = {});

}  // namespace sphark
