#include "sphark/boundaries/static_profile.hpp"

#include "sphark/boundaries/relaxation.hpp"
#include "sphark/boundaries/wall_relaxation.hpp"
#include "sphark/kernels/kernels.hpp"

namespace sphark {

template <int D>
NodeDensityProfile<D> node_density_profile(const Wall<D>& wall, const std::vector<Real>& x, Real h,
                                           GhostMap map, Real layer_width,
                                           const std::optional<PeriodicBox<D>>& box) {
  const std::size_t n = x.size() / D;
  GhostLayer<D> ghosts;
  GhostOptions opt;
  opt.width = layer_width;
  opt.map = map;
  opt.on_invalid = OnInvalid::Skip;
  const GhostReport rep = ghosts.append(wall, x.data(), nullptr, n, opt);

  NodeDensityProfile<D> out;
  out.invalid = rep.invalid;
  const std::size_t g = ghosts.size();
  std::vector<Real> all(x);
  all.insert(all.end(), ghosts.positions(), ghosts.positions() + D * g);

  NeighbourSearch<D> search(box);
  search.build(all.data(), n + g, WendlandC4<D>::support * h);
  std::vector<Real> nd(n + g);
  node_density(search, all.data(), n + g, h, nd.data());

  out.s_inner.resize(n);
  std::visit(
      [&](const auto& w) {
        for (std::size_t i = 0; i < n; ++i) out.s_inner[i] = w.locate(Eigen::Map<const Vec<D>>(x.data() + D * i)).s;
      },
      wall);
  out.n_inner.assign(nd.begin(), nd.begin() + n);
  out.n_ghost.assign(nd.begin() + n, nd.end());
  out.s_ghost.assign(ghosts.wall_s(), ghosts.wall_s() + g);
  out.x_ghost.assign(ghosts.positions(), ghosts.positions() + D * g);
  return out;
}

template <int D>
RelaxedSet<D> relaxed_set(const Wall<D>& wall, const PeriodicBox<D>& relax_box, std::size_t n_box,
                          GhostMap relax_map, const std::optional<PeriodicBox<D>>& wall_box,
                          const std::function<bool(const Vec<D>&)>& may_move, Real band_H, unsigned seed,
                          const RelaxOptions& opt) {
  RelaxedSet<D> out;
  std::vector<Real> x = jittered_lattice<D>(n_box, relax_box, 0.8, seed);
  out.bulk = relax_uniform<D>(x, relax_box, opt);
  const Real H = WendlandC4<D>::support * out.bulk.h;
  std::vector<char> movable;
  std::visit(
      [&](const auto& w) {
        for (std::size_t i = 0; i < x.size() / D; ++i) {
          const Vec<D> p = Eigen::Map<const Vec<D>>(x.data() + D * i);
          const Real s = w.locate(p).s;
          if (s >= 0) continue;
          out.x.insert(out.x.end(), x.begin() + D * i, x.begin() + D * i + D);
          movable.push_back(s > -band_H * H && may_move(p));
        }
      },
      wall);
  out.wall = relax_near_wall<D>(out.x, wall, relax_map, out.bulk.h, movable, wall_box, opt);
  return out;
}

BinMean mean_in_range(const std::vector<Real>& s, const std::vector<Real>& n, Real lo, Real hi) {
  BinMean b;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i] > lo && s[i] <= hi) {
      b.mean += n[i];
      ++b.count;
    }
  if (b.count) b.mean /= static_cast<Real>(b.count);
  return b;
}

template RelaxedSet<2> relaxed_set<2>(const Wall<2>&, const PeriodicBox<2>&, std::size_t, GhostMap,
                                      const std::optional<PeriodicBox<2>>&, const std::function<bool(const Vec<2>&)>&,
                                      Real, unsigned, const RelaxOptions&);
template RelaxedSet<3> relaxed_set<3>(const Wall<3>&, const PeriodicBox<3>&, std::size_t, GhostMap,
                                      const std::optional<PeriodicBox<3>>&, const std::function<bool(const Vec<3>&)>&,
                                      Real, unsigned, const RelaxOptions&);
template NodeDensityProfile<2> node_density_profile<2>(const Wall<2>&, const std::vector<Real>&, Real, GhostMap, Real,
                                                       const std::optional<PeriodicBox<2>>&);
template NodeDensityProfile<3> node_density_profile<3>(const Wall<3>&, const std::vector<Real>&, Real, GhostMap, Real,
                                                       const std::optional<PeriodicBox<3>>&);

}  // namespace sphark
