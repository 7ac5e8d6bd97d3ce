// Data of seed 001 Figures 2, 4 and 5 (N = 41), one CSV per figure panel.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sphark/io/atomic_file.hpp"
#include "scene.hpp"
#include "sphark/derivatives1d/bvp1d.hpp"

namespace scene {

using namespace sphark::d1;

namespace {
const Method kMethods[] = {Method::Cspm, Method::Bim, Method::Icspm};

// Direct problem: <f''>_i of each method next to f''(x_i); BIM is empty on the boundary particles.
void direct_figure(const std::filesystem::path& file, const Particles1D& p, Real h) {
  const TestFunction fn = seed_function();
  const Eigen::VectorXd f = p.x.unaryExpr(fn.f);
  sphark::AtomicFile out(file);
  out << "# h=" << h << " N=" << p.size() << "\nx,exact,CSPM,BIM,ICSPM\n";
  Eigen::MatrixXd d(p.size(), 3);
  for (int k = 0; k < 3; ++k) d.col(k) = second_derivative(kMethods[k], p, h) * f;
  for (Index i = 0; i < p.size(); ++i) {
    out << p.x[i] << ',' << fn.f2(p.x[i]);
    for (int k = 0; k < 3; ++k) {
      out << ',';
      if (row_defined(kMethods[k], p, i)) out << d(i, k);
    }
    out << '\n';
  }
  out.commit();
}

// Boundary-value problem (5.18): u_i of each method next to f(x_i).
void bvp_figure(const std::filesystem::path& file, const Particles1D& p, Real h) {
  const TestFunction fn = seed_function();
  const Eigen::VectorXd g = p.x.unaryExpr(fn.f2);
  sphark::AtomicFile out(file);
  out << "# h=" << h << " N=" << p.size() << "\nx,exact,CSPM,BIM,ICSPM\n";
  Eigen::MatrixXd u(p.size(), 3);
  for (int k = 0; k < 3; ++k)
    u.col(k) = solve_dirichlet(second_derivative(kMethods[k], p, h), p, g, fn.f(0.0), fn.f(1.0));
  for (Index i = 0; i < p.size(); ++i)
    out << p.x[i] << ',' << fn.f(p.x[i]) << ',' << u(i, 0) << ',' << u(i, 1) << ',' << u(i, 2) << '\n';
  out.commit();
}
// Beyond the paper: kappa_i (4.14) against the distance to the nearest end in units of h, with the
// direct ICSPM and CSPM errors, for 10 nested random sets with N = 641, c = 2. kappa passes
// through 0 at about 0.3 h from the boundary: particles there get large ICSPM errors.
void kappa_data(const std::filesystem::path& file, const Options& opt) {
  const TestFunction fn = seed_function();
  sphark::AtomicFile out(file);
  out << "seed,s,kappa,err_icspm,err_cspm\n";
  for (std::uint64_t seed = opt.seed; seed < opt.seed + 10; ++seed) {
    const Particles1D p = random_particles(641, seed);
    const Real h = smoothing_length(p, 2);
    const Moments1D m = moments(p, h);
    const Eigen::VectorXd f = p.x.unaryExpr(fn.f);
    const Eigen::VectorXd ei = icspm_second_derivative(p, h) * f, ec = cspm_second_derivative(p, h) * f;
    for (Index i = 0; i < p.size(); ++i) {
      const Real s = std::min(p.x[i] - p.x_left, p.x_right - p.x[i]) / h;
      if (s >= 2.5) continue;
      out << seed << ',' << s << ',' << m.kappa[i] << ',' << std::abs(ei[i] - fn.f2(p.x[i])) << ','
          << std::abs(ec[i] - fn.f2(p.x[i])) << '\n';
    }
  }
  out.commit();
}
}  // namespace

void write_figure_data(const Options& opt) {
  const Particles1D uniform = uniform_particles(41);
  direct_figure(opt.out / "fig2.csv", uniform, 1.0 / 20);  // seed 001 Figure 2: N = 41, h = 1/20
  const Particles1D random = random_particles(41, opt.seed);
  direct_figure(opt.out / "fig4_c2.csv", random, smoothing_length(random, 2));  // Figure 4 top
  direct_figure(opt.out / "fig4_c3.csv", random, smoothing_length(random, 3));  // Figure 4 bottom
  bvp_figure(opt.out / "fig5.csv", random, smoothing_length(random, 2));        // Figure 5: c = 2
  kappa_data(opt.out / "kappa.csv", opt);
}

}  // namespace scene
