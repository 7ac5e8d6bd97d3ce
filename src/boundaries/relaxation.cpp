#include "sphark/boundaries/relaxation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <cstdio>
#include <cstdlib>

#include "sphark/kernels/kernels.hpp"
#include "sphark/run/signals.hpp"

namespace sphark {

namespace {
template <int D>
struct Stats {
  Real mean = 0, rel_std = 0, max_rel_dev = 0;
};
template <int D>
Stats<D> stats(const std::vector<Real>& n) {
  Stats<D> s;
  for (Real v : n) s.mean += v;
  s.mean /= static_cast<Real>(n.size());
  Real var = 0;
  for (Real v : n) {
    var += (v - s.mean) * (v - s.mean);
    s.max_rel_dev = std::max(s.max_rel_dev, std::abs(v / s.mean - 1));
  }
  s.rel_std = std::sqrt(var / static_cast<Real>(n.size())) / s.mean;
  return s;
}
}  // namespace

template <int D>
void node_density(const NeighbourSearch<D>& search, const Real* x, std::size_t n, Real h, Real* out) {
  using K = WendlandC4<D>;
  const NeighbourList& list = search.list();
  const Real H = K::support * h;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    Real sum = K::w(0, h);  // seed 004, eq. (3), self term included
    for (std::size_t k = list.begin(i); k < list.end(i); ++k) {
      const Real r = search.separation(x, i, list.indices[k]).norm();
      if (r < H) sum += K::w(r, h);
    }
    out[i] = sum;
  }
}

template <int D>
std::vector<Real> random_points(std::size_t n, const PeriodicBox<D>& box, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Real> U(0, 1);
  std::vector<Real> x(D * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < D; ++k) x[D * i + k] = box.lo[k] + (box.hi[k] - box.lo[k]) * U(rng);
  return x;
}

template <int D>
std::vector<Real> jittered_lattice(std::size_t n, const PeriodicBox<D>& box, Real jitter, unsigned seed) {
  const Vec<D> L = box.length();
  const Real dx = std::pow(L.prod() / static_cast<Real>(n), 1.0 / D);
  std::array<std::size_t, D> cells{};
  std::size_t total = 1;
  for (int k = 0; k < D; ++k) total *= cells[k] = std::max<std::size_t>(1, std::lround(L[k] / dx));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Real> U(-0.5, 0.5);
  std::vector<Real> x(D * total);
  for (std::size_t c = 0; c < total; ++c) {
    std::size_t rest = c;
    Vec<D> p;
    for (int k = 0; k < D; ++k) {
      const Real a = L[k] / static_cast<Real>(cells[k]);
      p[k] = box.lo[k] + a * (static_cast<Real>(rest % cells[k]) + 0.5 + jitter * U(rng));
      rest /= cells[k];
    }
    Eigen::Map<Vec<D>>(x.data() + D * c) = box.wrap(p);
  }
  return x;
}

template <int D>
RelaxReport relax_uniform(std::vector<Real>& x, const PeriodicBox<D>& box, const RelaxOptions& opt) {
  using K = WendlandC4<D>;
  const std::size_t n = x.size() / D;
  const Real volume = box.length().prod();
  RelaxReport rep;
  rep.dx = std::pow(volume / static_cast<Real>(n), 1.0 / D);
  rep.h = opt.h_over_dx * rep.dx;
  const Real H = K::support * rep.h;
  const Real skin = 0.5 * rep.dx;
  const Real max_step = 0.2 * rep.dx;

  NeighbourSearch<D> search(box);
  search.build(x.data(), n, H + skin);
  std::vector<Real> nd(n), dx(D * n);
  for (int it = 0;; ++it) {
    throw_if_stop_requested();  // SIGINT/SIGTERM (run/signals.hpp): a long relaxation ends here
    if (search.max_displacement_since_build(x.data()) > 0.5 * skin) search.build(x.data(), n, H + skin);
    node_density(search, x.data(), n, rep.h, nd.data());
    const Stats<D> st = stats<D>(nd);
    rep.iterations = it;
    rep.mean = st.mean;
    rep.rel_std = st.rel_std;
    rep.max_rel_dev = st.max_rel_dev;
    if (std::getenv("SPHARK_RELAX_TRACE"))  // progress on stderr when set
      std::fprintf(stderr, "relax %d std %.4g max %.4g\n", it, st.rel_std, st.max_rel_dev);
    if (st.rel_std <= opt.tolerance || it >= opt.max_iterations) break;

    const NeighbourList& list = search.list();
    const Real scale = opt.beta * rep.dx * rep.dx / st.mean;
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      Vec<D> grad = Vec<D>::Zero();  // grad n_i
      for (std::size_t k = list.begin(i); k < list.end(i); ++k) {
        const Vec<D> d = search.separation(x.data(), i, list.indices[k]);
        const Real r = d.norm();
        if (r < H && r > 0) grad += K::f_over_r(r, rep.h) * d;
      }
      Vec<D> step = -scale * grad;
      const Real len = step.norm();
      if (len > max_step) step *= max_step / len;
      Eigen::Map<Vec<D>>(dx.data() + D * i) = step;
    }
    for (std::size_t i = 0; i < n; ++i) {
      Eigen::Map<Vec<D>> xi(x.data() + D * i);
      xi = box.wrap(Vec<D>(xi + Eigen::Map<const Vec<D>>(dx.data() + D * i)));
    }
  }
  return rep;
}

template void node_density<2>(const NeighbourSearch<2>&, const Real*, std::size_t, Real, Real*);
template void node_density<3>(const NeighbourSearch<3>&, const Real*, std::size_t, Real, Real*);
template std::vector<Real> random_points<2>(std::size_t, const PeriodicBox<2>&, unsigned);
template std::vector<Real> random_points<3>(std::size_t, const PeriodicBox<3>&, unsigned);
template std::vector<Real> jittered_lattice<2>(std::size_t, const PeriodicBox<2>&, Real, unsigned);
template std::vector<Real> jittered_lattice<3>(std::size_t, const PeriodicBox<3>&, Real, unsigned);
template RelaxReport relax_uniform<2>(std::vector<Real>&, const PeriodicBox<2>&, const RelaxOptions&);
template RelaxReport relax_uniform<3>(std::vector<Real>&, const PeriodicBox<3>&, const RelaxOptions&);

}  // namespace sphark
