#include "sphark/boundaries/wall_relaxation.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "sphark/kernels/kernels.hpp"
#include "sphark/run/signals.hpp"

namespace sphark {
namespace {

// The number density sum_j W(r_ij, h) of every movable particle (Wendland C4; neighbours among
// the particles and ghosts `all` of the last build of `search`) in nd, its gradient in step.
template <int D>
void number_density(const NeighbourSearch<D>& search, const std::vector<Real>& all, Real h,
                    const std::vector<char>& movable, std::vector<Real>& nd, std::vector<Real>& step) {
  using K = WendlandC4<D>;
  const std::size_t n = nd.size();
  const Real H = K::support * h;
  const NeighbourList& list = search.list();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (!movable[i]) continue;
    Real sum = K::w(0, h);  // seed 004, eq. (3)
    Vec<D> grad = Vec<D>::Zero();
    for (std::size_t k = list.begin(i); k < list.end(i); ++k) {
      const Vec<D> d = search.separation(all.data(), i, list.indices[k]);
      const Real r = d.norm();
      if (r >= H) continue;
      sum += K::w(r, h);
      if (r > 0) grad += K::f_over_r(r, h) * d;
    }
    nd[i] = sum;
    Eigen::Map<Vec<D>>(step.data() + D * i) = grad;
  }
}

// The mean of nd over the movable particles, its relative standard deviation and the largest
// relative deviation from it.
void density_spread(const std::vector<Real>& nd, const std::vector<char>& movable, RelaxReport& rep) {
  const std::size_t n = nd.size();
  Real mean = 0, var = 0, maxdev = 0;
  std::size_t m = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (movable[i]) mean += nd[i], ++m;
  mean /= static_cast<Real>(m);
  for (std::size_t i = 0; i < n; ++i)
    if (movable[i]) {
      var += (nd[i] - mean) * (nd[i] - mean);
      maxdev = std::max(maxdev, std::abs(nd[i] / mean - 1));
    }
  rep.mean = mean;
  rep.rel_std = std::sqrt(var / static_cast<Real>(m)) / mean;
  rep.max_rel_dev = maxdev;
}

// Moves every movable particle by -scale x its density gradient (at most max_step), reflected
// back into the fluid side of the wall and wrapped into the box.
template <int D>
void move_down_gradient(std::vector<Real>& x, const std::vector<Real>& step, const std::vector<char>& movable,
                        const Wall<D>& wall, Real scale, Real max_step, const PeriodicBox<D>* bp) {
  const std::size_t n = x.size() / D;
  std::visit(
      [&](const auto& w) {
        for (std::size_t i = 0; i < n; ++i) {
          if (!movable[i]) continue;
          Eigen::Map<Vec<D>> xi(x.data() + D * i);
          Vec<D> dxi = -scale * Eigen::Map<const Vec<D>>(step.data() + D * i);
          const Real len = dxi.norm();
          if (len > max_step) dxi *= max_step / len;
          Vec<D> p = xi + dxi;
          const WallPoint<D> wp = w.locate(p);
          if (wp.s > 0) p -= 2 * wp.s * wp.normal;  // back into the fluid side
          xi = bp ? bp->wrap(p) : p;
        }
      },
      wall);
}

}  // namespace

template <int D>
RelaxReport relax_near_wall(std::vector<Real>& x, const Wall<D>& wall, GhostMap map, Real h,
                            const std::vector<char>& movable, const std::optional<PeriodicBox<D>>& box,
                            const RelaxOptions& opt) {
  using K = WendlandC4<D>;
  const std::size_t n = x.size() / D;
  const Real H = K::support * h;
  RelaxReport rep;
  rep.h = h;
  rep.dx = h / opt.h_over_dx;
  const Real max_step = 0.2 * rep.dx;

  GhostLayer<D> ghosts;
  GhostOptions gopt;
  gopt.width = 2 * H;  // every ghost within H of an inner particle within H of the wall
  gopt.map = map;
  gopt.on_invalid = OnInvalid::Skip;
  NeighbourSearch<D> search(box);
  std::vector<Real> all, nd(n), step(D * n, 0.0);
  const PeriodicBox<D>* bp = box ? &*box : nullptr;

  for (int it = 0;; ++it) {
    throw_if_stop_requested();  // SIGINT/SIGTERM (run/signals.hpp): a long relaxation ends here
    ghosts.clear();
    ghosts.append(wall, x.data(), nullptr, n, gopt, bp);
    all.assign(x.begin(), x.end());
    all.insert(all.end(), ghosts.positions(), ghosts.positions() + D * ghosts.size());
    search.build(all.data(), n + ghosts.size(), H);

    number_density(search, all, h, movable, nd, step);
    rep.iterations = it;
    density_spread(nd, movable, rep);
    if (std::getenv("SPHARK_RELAX_TRACE"))
      std::fprintf(stderr, "wall relax %d std %.4g max %.4g ghosts %zu\n", it, rep.rel_std, rep.max_rel_dev,
                   ghosts.size());
    if (rep.rel_std <= opt.tolerance || it >= opt.max_iterations) break;

    const Real scale = opt.beta * rep.dx * rep.dx / rep.mean;
    move_down_gradient(x, step, movable, wall, scale, max_step, bp);
  }
  return rep;
}

template RelaxReport relax_near_wall<2>(std::vector<Real>&, const Wall<2>&, GhostMap, Real, const std::vector<char>&,
                                        const std::optional<PeriodicBox<2>>&, const RelaxOptions&);
template RelaxReport relax_near_wall<3>(std::vector<Real>&, const Wall<3>&, GhostMap, Real, const std::vector<char>&,
                                        const std::optional<PeriodicBox<3>>&, const RelaxOptions&);

}  // namespace sphark
