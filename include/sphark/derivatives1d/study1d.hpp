#pragma once
// Convergence studies of seed 001 §V: test functions, errors e_N, observed orders p_N and the
// specifications of the paper's Tables 1-5.
#include <cstdint>
#include <vector>

#include "sphark/derivatives1d/operators1d.hpp"

namespace sphark::d1 {

struct TestFunction {
  const char* name;
  Real (*f)(Real);
  Real (*f2)(Real);  // exact second derivative
};
TestFunction seed_function();     // seed 001 §V: f = x^2 + cos(pi x), f'' = 2 - pi^2 cos(pi x)   (5.18)
TestFunction exp_sin_function();  // beyond the paper: f = e^x sin(3x), f'' = e^x (6 cos 3x - 8 sin 3x)

enum class Problem { Direct, Bvp };
enum class Layout { Uniform, Random };

// h = c * max|Omega_i| (seed 001 (5.19), = c dx for uniform particles), or, with
// squared_run_index, h = k^2 * max|Omega_i| with k = 1, 2, ... the simulation number (§V.I, Table 2).
struct SmoothingRule {
  Real c = 2;
  bool squared_run_index = false;
  Real factor(Index k) const { return squared_run_index ? Real(k * k) : c; }
};

Particles1D make_particles(Layout layout, Index n, std::uint64_t seed);

// e_N of seed 001 §V.I: the max-norm error over the particles where the method is defined
// (direct problem: <f''>_i vs f''(x_i); boundary-value problem (5.18): u_i vs f(x_i)).
Real error_direct(Method m, const Particles1D& p, Real h, const TestFunction& fn);
Real error_bvp(Method m, const Particles1D& p, Real h, const TestFunction& fn);

// p_N = log(e_{(N+1)/2} / e_N) / log 2   (seed 001 §V.I)
Real observed_order(Real e_coarse, Real e_fine);

struct Column {
  Method method;
  SmoothingRule rule;
};
struct TableSpec {
  int number;
  Problem problem;
  Layout layout;
  std::vector<Column> columns;
};
struct TableRow {
  Method method;
  Index n;
  Real h;
  Real error;
  Real order;  // NaN for the first row of a method
};

TableSpec paper_table(int number);  // 1..5 as in seed 001
std::vector<Index> paper_sizes(Index count = 8);  // 11, 21, 41, ..., (count entries; 8 -> 1281)

// Rows method by method, sizes in order; k (for the squared rule) is the 1-based position in `sizes`.
std::vector<TableRow> compute_table(const TableSpec& spec, const std::vector<Index>& sizes, std::uint64_t seed,
                                    const TestFunction& fn);

}  // namespace sphark::d1
