#include "sphark/boundaries/static_profile.hpp"

#include "sphark/boundaries/relaxation.hpp"
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

template NodeDensityProfile<2> node_density_profile<2>(const Wall<2>&, const std::vector<Real>&, Real, GhostMap, Real,
                                                       const std::optional<PeriodicBox<2>>&);
template NodeDensityProfile<3> node_density_profile<3>(const Wall<3>&, const std::vector<Real>&, Real, GhostMap, Real,
                                                       const std::optional<PeriodicBox<3>>&);

}  // namespace sphark
