// The cost side: wall time to assemble, apply (one mat-vec) and solve (5.18) with each operator,
// next to its error, on uniform particles with the paper's smoothing lengths.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "sphark/io/atomic_file.hpp"
#include "scene.hpp"
#include "sphark/derivatives1d/bvp1d.hpp"

namespace scene {

using namespace sphark::d1;

namespace {
// Wall time of one fn() call in seconds: the best of 5 batches, each batch repeating fn() for at
// least 4 ms (the machine is shared, so the minimum is the least noisy estimate).
template <class F>
double time_it(F&& fn) {
  using clock = std::chrono::steady_clock;
  double best = 1e300;
  for (int batch = 0; batch < 5; ++batch) {
    int calls = 0;
    const auto t0 = clock::now();
    double elapsed = 0;
    do {
      fn();
      ++calls;
      elapsed = std::chrono::duration<double>(clock::now() - t0).count();
    } while (elapsed < 4e-3);
    best = std::min(best, elapsed / calls);
  }
  return best;
}
}  // namespace

void write_timing(const Options& opt, const std::vector<Index>& sizes) {
  struct Config {
    Method method;
    SmoothingRule rule;
    const char* label;
  };
  const Config configs[] = {{Method::Cspm, {2, false}, "CSPM c=2"},
                            {Method::Icspm, {2, false}, "ICSPM c=2"},
                            {Method::Bim, {2, false}, "BIM c=2"},
                            {Method::Bim, {0, true}, "BIM c=k^2"}};
  const TestFunction fn = seed_function();
  sphark::AtomicFile out(opt.out / "timing.csv");
  out << "config,method,N,h,nnz,assemble_s,apply_s,solve_s,e_direct,e_bvp\n";
  std::printf("\nCost (uniform particles; mean wall time per call)\n\n");
  std::printf("| config | N | nnz | assemble [us] | apply [us] | solve (5.18) [us] | e_N direct | e_N BVP |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Config& c : configs) {
    for (std::size_t k = 0; k < sizes.size(); ++k) {
      const Particles1D p = uniform_particles(sizes[k]);
      const Real h = smoothing_length(p, c.rule.factor(static_cast<Index>(k) + 1));
      const SparseMatrix L = second_derivative(c.method, p, h);
      const Eigen::VectorXd f = p.x.unaryExpr(fn.f), g = p.x.unaryExpr(fn.f2);
      Eigen::VectorXd y(p.size());
      const double t_asm = time_it([&] { volatile auto nnz = second_derivative(c.method, p, h).nonZeros(); (void)nnz; });
      const double t_app = time_it([&] { y.noalias() = L * f; });
      const double t_sol = time_it([&] { y = solve_dirichlet(L, p, g, fn.f(0.0), fn.f(1.0)); });
      const Real ed = error_direct(c.method, p, h, fn), eb = error_bvp(c.method, p, h, fn);
      char line[256];
      std::snprintf(line, sizeof line, "%s,%s,%ld,%.6g,%ld,%.6e,%.6e,%.6e,%.6e,%.6e\n", c.label,
                    method_name(c.method), static_cast<long>(p.size()), h, static_cast<long>(L.nonZeros()), t_asm,
                    t_app, t_sol, ed, eb);
      out << line;
      std::printf("| %s | %ld | %ld | %.1f | %.2f | %.1f | %.3e | %.3e |\n", c.label, static_cast<long>(p.size()),
                  static_cast<long>(L.nonZeros()), t_asm * 1e6, t_app * 1e6, t_sol * 1e6, ed, eb);
    }
  }
  out.commit();
}

}  // namespace scene
