#include "sphark/derivatives1d/study1d.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "sphark/derivatives1d/bvp1d.hpp"

namespace sphark::d1 {

namespace {
Real seed_f(Real x) { return x * x + std::cos(kPi * x); }
Real seed_f2(Real x) { return 2 - kPi * kPi * std::cos(kPi * x); }
Real es_f(Real x) { return std::exp(x) * std::sin(3 * x); }
Real es_f2(Real x) { return std::exp(x) * (6 * std::cos(3 * x) - 8 * std::sin(3 * x)); }

Eigen::VectorXd sample(Real (*g)(Real), const Eigen::VectorXd& x) { return x.unaryExpr(g); }
}  // namespace

TestFunction seed_function() { return {"x^2+cos(pi x)", seed_f, seed_f2}; }
TestFunction exp_sin_function() { return {"exp(x) sin(3x)", es_f, es_f2}; }

Particles1D make_particles(Layout layout, Index n, std::uint64_t seed) {
  return layout == Layout::Uniform ? uniform_particles(n) : random_particles(n, seed);
}

Real error_direct(Method m, const Particles1D& p, Real h, const TestFunction& fn) {
  const Eigen::VectorXd d2 = second_derivative(m, p, h) * sample(fn.f, p.x);
  Real e = 0;
  for (Index i = 0; i < p.size(); ++i)
    if (row_defined(m, p, i)) e = std::max(e, std::abs(d2[i] - fn.f2(p.x[i])));
  return e;
}

Real error_bvp(Method m, const Particles1D& p, Real h, const TestFunction& fn) {
  const Eigen::VectorXd u = solve_dirichlet(second_derivative(m, p, h), p, sample(fn.f2, p.x),
                                            fn.f(p.x[p.left()]), fn.f(p.x[p.right()]));
  return (u - sample(fn.f, p.x)).cwiseAbs().maxCoeff();
}

Real observed_order(Real e_coarse, Real e_fine) { return std::log(e_coarse / e_fine) / std::log(2.0); }

TableSpec paper_table(int number) {
  const SmoothingRule c2{2, false}, k2{0, true};
  switch (number) {  // seed 001 §V: c = 2 for CSPM/ICSPM; BIM c = 2 in Table 1, h = k^2 dx after it
    case 1: return {1, Problem::Direct, Layout::Uniform, {{Method::Cspm, c2}, {Method::Bim, c2}, {Method::Icspm, c2}}};
    case 2: return {2, Problem::Direct, Layout::Uniform, {{Method::Bim, k2}}};
    case 3: return {3, Problem::Bvp, Layout::Uniform, {{Method::Cspm, c2}, {Method::Bim, k2}, {Method::Icspm, c2}}};
    case 4: return {4, Problem::Direct, Layout::Random, {{Method::Cspm, c2}, {Method::Bim, k2}, {Method::Icspm, c2}}};
    case 5: return {5, Problem::Bvp, Layout::Random, {{Method::Cspm, c2}, {Method::Bim, k2}, {Method::Icspm, c2}}};
  }
  throw std::invalid_argument("paper_table: number must be 1..5");
}

std::vector<Index> paper_sizes(Index count) {
  std::vector<Index> n;
  for (Index k = 0, m = 11; k < count; ++k, m = 2 * m - 1) n.push_back(m);
  return n;
}

std::vector<TableRow> compute_table(const TableSpec& spec, const std::vector<Index>& sizes, std::uint64_t seed,
                                    const TestFunction& fn) {
  std::vector<TableRow> rows;
  for (const Column& col : spec.columns) {
    Real previous = std::numeric_limits<Real>::quiet_NaN();
    for (std::size_t k = 0; k < sizes.size(); ++k) {
      const Particles1D p = make_particles(spec.layout, sizes[k], seed);
      const Real h = smoothing_length(p, col.rule.factor(static_cast<Index>(k) + 1));
      const Real e = spec.problem == Problem::Direct ? error_direct(col.method, p, h, fn)
                                                     : error_bvp(col.method, p, h, fn);
      rows.push_back({col.method, sizes[k], h, e, observed_order(previous, e)});
      previous = e;
    }
  }
  return rows;
}

}  // namespace sphark::d1
