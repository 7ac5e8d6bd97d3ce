// Variable-radius neighbour lists (pairs with |x_a - x_b| < max(r_a, r_b), r = 2 h (1 + 0.25),
// h = 1.2 (m / rho)^(1/3): the SPMHD scheme's lists) on collapse-like distributions, issue #15:
// a sphere of 10^5 particles with rho ~ 1 / (1 + r^2 / r_c^2), central/edge contrast C, in a cube
// of side 4 of ambient gas at 1/30 of the edge density with the same particle mass (the collapse's
// box, open boundaries here). Three builders of the same lists:
//   grid       NeighbourSearch<3> (cells sized by the largest radius), as the scheme uses it
//   kdtree     KdTreeNeighbourSearch<3> (per-node largest radius, one traversal per particle)
//   nanoflann  nanoflann's kd-tree: a gather search of radius r_i per particle, then the
//              transpose merged in (nanoflann has no per-point radii: max(r_a, r_b) = gather
//              of a or of b), rows sorted
// Scenario (first argument): 0 the uniform sphere alone; 1..4 the uniform sphere in ambient gas
// at 1/2, 1/4, 1/8, 1/30 of its density (h ratio 1.26 .. 3.1: the collapse at t = 0 is 4);
// 5..8 centrally condensed, C = 1e2, 1e4, 1e5, 1e7, in ambient gas at 1/30 of the edge density.
// Counters: ns per particle per build, pairs per particle, the radius ratios max/median and
// max/min, Q = mean (r_max / r_i)^3 (the rule's predictor: sphark/neighbours/neighbour_method.hpp)
// and the cell grid's candidates per particle (the pairs it distance-tests).
//   build/bin/bench_neighbours_wide_h --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>
#include <omp.h>

#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "sphark/neighbours/kd_tree_search.hpp"
#include "sphark/neighbours/neighbour_search.hpp"

using namespace sphark;

namespace {

struct Scene {
  std::vector<Real> x, radii;
  Real r_max = 0;
};

// rho = rho_0 / (1 + r^2 / rc^2) on r < 1 (uniform for C = 1); M(<r) ~ r - rc atan(r / rc).
constexpr int kScenes = 9;
constexpr Real kCentral[kScenes] = {1, 1, 1, 1, 1, 1e2, 1e4, 1e5, 1e7};  // central / edge density
constexpr Real kAmbient[kScenes] = {0, 2, 4, 8, 30, 30, 30, 30, 30};    // edge / ambient density (0: none)

// The Morton (Z-order) permutation of the points x (D per point) in [lo, lo + extent)^D, `bits`
// bits per axis.
template <int D>
std::vector<std::uint32_t> morton_order(const std::vector<Real>& x, Real lo, Real extent, int bits) {
  const std::size_t n = x.size() / D;
  std::vector<std::uint64_t> code(n);
  for (std::size_t a = 0; a < n; ++a) {
    std::uint64_t c = 0;
    for (int k = 0; k < D; ++k) {
      const Real u = std::clamp((x[D * a + k] - lo) / extent, 0.0, 0.999999);
      const auto q = static_cast<std::uint64_t>(u * static_cast<Real>(std::uint64_t{1} << bits));
      for (int b = 0; b < bits; ++b) c |= ((q >> b) & 1u) << (D * b + k);
    }
    code[a] = c;
  }
  std::vector<std::uint32_t> order(n);
  for (std::size_t a = 0; a < n; ++a) order[a] = static_cast<std::uint32_t>(a);
  std::sort(order.begin(), order.end(), [&](std::uint32_t p, std::uint32_t q) { return code[p] < code[q]; });
  return order;
}

// The points (D per point) and radii in the order `order`, with their largest radius.
template <int D>
Scene in_order(const std::vector<Real>& x, const std::vector<Real>& radii, const std::vector<std::uint32_t>& order) {
  Scene t;
  for (std::uint32_t a : order) {
    t.x.insert(t.x.end(), x.begin() + D * a, x.begin() + D * (a + 1));
    t.radii.push_back(radii[a]);
  }
  t.r_max = *std::max_element(t.radii.begin(), t.radii.end());
  return t;
}

Scene make_scene(int scenario) {
  const std::size_t n_sphere = 100000;
  const Real C = kCentral[scenario];
  const bool ambient = kAmbient[scenario] > 0;
  const Real rc = C > 1 ? 1 / std::sqrt(C - 1) : 0;
  auto enclosed = [&](Real r) { return C > 1 ? r - rc * std::atan(r / rc) : r * r * r; };
  const Real M = 1, m = M / n_sphere;
  // rho_0 from the total mass: M = 4 pi rho_0 rc^2 (1 - rc atan(1/rc)), or rho_0 = 3 M / (4 pi)
  const Real rho0 = C > 1 ? M / (4 * kPi * rc * rc * enclosed(1.0)) : 3 * M / (4 * kPi);
  auto rho = [&](Real r) { return C > 1 ? rho0 / (1 + r * r / (rc * rc)) : rho0; };
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<Real> U(0, 1);
  Scene s;
  auto add = [&](const Vec<3>& p, Real density) {
    s.x.insert(s.x.end(), {p[0], p[1], p[2]});
    s.radii.push_back(2 * 1.25 * 1.2 * std::cbrt(m / density));
  };
  for (std::size_t a = 0; a < n_sphere; ++a) {
    const Real target = U(rng) * enclosed(1.0);
    Real lo = 0, hi = 1;
    for (int it = 0; it < 60; ++it) (enclosed(0.5 * (lo + hi)) < target ? lo : hi) = 0.5 * (lo + hi);
    const Real r = 0.5 * (lo + hi), mu = 2 * U(rng) - 1, ph = 2 * kPi * U(rng), st = std::sqrt(1 - mu * mu);
    add(Vec<3>(r * st * std::cos(ph), r * st * std::sin(ph), r * mu), rho(r));
  }
  if (ambient) {
    const Real rho_amb = rho(1.0) / kAmbient[scenario];
    const auto n_amb = static_cast<std::size_t>(rho_amb * (64 - 4 * kPi / 3) / m);
    while (s.radii.size() < n_sphere + n_amb) {
      const Vec<3> p(4 * U(rng) - 2, 4 * U(rng) - 2, 4 * U(rng) - 2);
      if (p.norm() >= 1) add(p, rho_amb);
    }
  }
  // a spatial order (Morton, 2^10 per axis), as the scheme renumbers its particles
  const std::vector<std::uint32_t> order = morton_order<3>(s.x, -2, 4, 10);
  return in_order<3>(s.x, s.radii, order);
}

const Scene& scene(int k) {
  static std::vector<Scene> cache(kScenes);
  if (cache[k].radii.empty()) cache[k] = make_scene(k);
  return cache[k];
}

void radius_counters(benchmark::State& state, const Scene& s, std::size_t pairs) {
  std::vector<Real> r = s.radii;
  std::sort(r.begin(), r.end());
  const auto n = static_cast<double>(r.size());
  state.counters["particles"] = n;
  state.counters["max_over_median"] = r.back() / r[r.size() / 2];
  state.counters["max_over_min"] = r.back() / r.front();
  double q = 0;  // mean (r_max / r_i)^3: the grid's cell volume over the particle's search volume
  for (Real ri : r) q += std::pow(r.back() / ri, 3);
  state.counters["mean_cube_ratio"] = q / n;
  state.counters["pairs_per_particle"] = static_cast<double>(pairs) / n;
  state.counters["ns_per_particle"] =
      benchmark::Counter(n * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["threads"] = omp_get_max_threads();
}

// pairs the cell grid distance-tests: sum over particles of the particles in its 27 cells
double grid_candidates(const Scene& s) {
  double total = 0;
  // cells of side >= r_max over the bounding box, as bin() makes them
  Vec<3> lo = Vec<3>::Constant(1e300), hi = -lo;
  const std::size_t n = s.radii.size();
  for (std::size_t a = 0; a < n; ++a) {
    lo = lo.cwiseMin(Vec<3>(s.x[3 * a], s.x[3 * a + 1], s.x[3 * a + 2]));
    hi = hi.cwiseMax(Vec<3>(s.x[3 * a], s.x[3 * a + 1], s.x[3 * a + 2]));
  }
  std::array<long, 3> cells{};
  for (int k = 0; k < 3; ++k) cells[k] = std::max<long>(1, static_cast<long>((hi[k] - lo[k]) / s.r_max));
  std::vector<double> count(cells[0] * cells[1] * cells[2], 0);
  auto cell_of = [&](std::size_t a, int k) {
    return std::min<long>(cells[k] - 1, static_cast<long>((s.x[3 * a + k] - lo[k]) / ((hi[k] - lo[k]) / cells[k])));
  };
  for (std::size_t a = 0; a < n; ++a) count[(cell_of(a, 2) * cells[1] + cell_of(a, 1)) * cells[0] + cell_of(a, 0)] += 1;
  for (std::size_t a = 0; a < n; ++a) {
    const long cx = cell_of(a, 0), cy = cell_of(a, 1), cz = cell_of(a, 2);
    for (long z = std::max(0L, cz - 1); z <= std::min(cells[2] - 1, cz + 1); ++z)
      for (long y = std::max(0L, cy - 1); y <= std::min(cells[1] - 1, cy + 1); ++y)
        for (long x = std::max(0L, cx - 1); x <= std::min(cells[0] - 1, cx + 1); ++x)
          total += count[(z * cells[1] + y) * cells[0] + x];
  }
  return total / static_cast<double>(n);
}

void BM_Grid(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  const Scene& s = scene(static_cast<int>(state.range(0)));
  NeighbourSearch<3> ns;
  const std::size_t n = s.radii.size();
  ns.build(s.x.data(), n, s.r_max, nullptr, s.radii.data());
  for (auto _ : state) {
    ns.build(s.x.data(), n, s.r_max, nullptr, s.radii.data());
    benchmark::DoNotOptimize(ns.list().indices.data());
  }
  radius_counters(state, s, ns.list().pairs());
  state.counters["grid_candidates_per_particle"] = grid_candidates(s);
}

// Times search's builds of the lists of (x, radii), after checking once that they are the cell
// grid's (grid: a NeighbourSearch over the same box).
template <class Search, class Grid>
void time_builds(benchmark::State& state, Search& search, Grid& grid, const std::vector<Real>& x,
                 const std::vector<Real>& radii, Real r_max) {
  const std::size_t n = radii.size();
  search.build(x.data(), n, r_max, nullptr, radii.data());
  grid.build(x.data(), n, r_max, nullptr, radii.data());
  if (grid.list().offsets != search.list().offsets || grid.list().indices != search.list().indices)
    state.SkipWithError("the lists differ from the cell grid's");
  for (auto _ : state) {
    search.build(x.data(), n, r_max, nullptr, radii.data());
    benchmark::DoNotOptimize(search.list().indices.data());
  }
}

void BM_KdTree(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  const Scene& s = scene(static_cast<int>(state.range(0)));
  KdTreeNeighbourSearch<3> kd;
  NeighbourSearch<3> grid;
  time_builds(state, kd, grid, s.x, s.radii, s.r_max);
  radius_counters(state, s, kd.list().pairs());
  state.counters["allocating_builds"] = static_cast<double>(kd.allocations());
}

// nanoflann: dataset adaptor over the x array, and a result set that keeps indices only
struct Cloud {
  const Real* x;
  std::size_t n;
  std::size_t kdtree_get_point_count() const { return n; }
  Real kdtree_get_pt(std::size_t i, std::size_t k) const { return x[3 * i + k]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};
using FlannTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<Real, Cloud, Real, std::uint32_t>,
                                                      Cloud, 3, std::uint32_t>;
struct IndexSet {
  Real r2;
  std::vector<std::uint32_t>* out;
  std::size_t size() const { return out->size(); }
  bool full() const { return true; }
  bool addPoint(Real d2, std::uint32_t j) {
    if (d2 < r2) out->push_back(j);
    return true;
  }
  Real worstDist() const { return r2; }
};

// rows of the symmetric list: gather G_i (|x_i - x_j| < r_i), then G_i merged with the
// transpose {j : i in G_j}, sorted and without duplicates or i itself
void flann_lists(const FlannTree& tree, const Scene& s, NeighbourList& out, std::vector<std::size_t>& goff,
                 std::vector<std::uint32_t>& gather, std::vector<std::size_t>& toff, std::vector<std::uint32_t>& trans) {
  const std::size_t n = s.radii.size();
  goff.assign(n + 1, 0);
  gather.clear();
  std::vector<std::uint32_t> row;
  for (std::size_t i = 0; i < n; ++i) {
    row.clear();
    IndexSet set{s.radii[i] * s.radii[i], &row};
    tree.findNeighbors(set, s.x.data() + 3 * i, nanoflann::SearchParams(32, 0, false));
    for (std::uint32_t j : row)
      if (j != i) gather.push_back(j);
    goff[i + 1] = gather.size();
  }
  toff.assign(n + 1, 0);
  for (std::uint32_t j : gather) ++toff[j + 1];
  for (std::size_t i = 0; i < n; ++i) toff[i + 1] += toff[i];
  trans.resize(gather.size());
  std::vector<std::size_t> cursor(toff.begin(), toff.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = goff[i]; k < goff[i + 1]; ++k) trans[cursor[gather[k]]++] = static_cast<std::uint32_t>(i);
  out.offsets.assign(n + 1, 0);
  out.indices.clear();
  for (std::size_t i = 0; i < n; ++i) {
    row.assign(gather.begin() + goff[i], gather.begin() + goff[i + 1]);
    row.insert(row.end(), trans.begin() + toff[i], trans.begin() + toff[i + 1]);
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    out.indices.insert(out.indices.end(), row.begin(), row.end());
    out.offsets[i + 1] = out.indices.size();
  }
}

void BM_Nanoflann(benchmark::State& state) {
  const Scene& s = scene(static_cast<int>(state.range(0)));
  const Cloud cloud{s.x.data(), s.radii.size()};
  NeighbourList list;
  std::vector<std::size_t> goff, toff;
  std::vector<std::uint32_t> gather, trans;
  {
    FlannTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    flann_lists(tree, s, list, goff, gather, toff, trans);
    NeighbourSearch<3> ns;
    ns.build(s.x.data(), s.radii.size(), s.r_max, nullptr, s.radii.data());
    if (ns.list().offsets != list.offsets || ns.list().indices != list.indices)
      state.SkipWithError("nanoflann lists differ from the cell grid's");
  }
  for (auto _ : state) {
    FlannTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));  // the build is part of the cost
    flann_lists(tree, s, list, goff, gather, toff, trans);
    benchmark::DoNotOptimize(list.indices.data());
  }
  radius_counters(state, s, list.pairs());
}

// 2D (session 17): the periodic unit square at density 1 with a central disc of radius 0.3 at
// density c (h ratio sqrt(c); the Orszag-Tang vortex's late density contrast is 5-10), 10^5
// particles, r = 2 h (1 + 0.25), h = 1.2 (m / rho)^(1/2); Morton order. Scenes c = kContrast2D[k].
constexpr int kScenes2D = 8;
constexpr Real kContrast2D[kScenes2D] = {1, 1.5, 2, 3, 4, 6, 9, 16};

Scene make_scene_2d(int k) {
  const Real c = kContrast2D[k], r_disc = 0.3, disc_area = kPi * r_disc * r_disc;
  const std::size_t n = 100000;
  const Real mass_total = (1 - disc_area) + c * disc_area, m = mass_total / static_cast<Real>(n);
  std::mt19937_64 rng(2026 + k);
  std::uniform_real_distribution<Real> U(0, 1);
  std::vector<Real> x, radii;
  const auto n_disc = static_cast<std::size_t>(c * disc_area / mass_total * static_cast<Real>(n));
  while (radii.size() < n) {
    const Real px = U(rng), py = U(rng);
    const bool inside = std::hypot(px - 0.5, py - 0.5) < r_disc;
    if (inside != (radii.size() < n_disc)) continue;  // the disc's particles first, then the rest
    x.insert(x.end(), {px, py});
    radii.push_back(2 * 1.25 * 1.2 * std::sqrt(m / (inside ? c : 1.0)));
  }
  return in_order<2>(x, radii, morton_order<2>(x, 0, 1, 16));
}

const Scene& scene_2d(int k) {
  static std::vector<Scene> cache(kScenes2D);
  if (cache[k].radii.empty()) cache[k] = make_scene_2d(k);
  return cache[k];
}

PeriodicBox<2> unit_square() {
  PeriodicBox<2> box;
  box.lo = Vec<2>::Zero();
  box.hi = Vec<2>::Ones();
  box.periodic = {true, true};
  return box;
}

void counters_2d(benchmark::State& state, const Scene& s, std::size_t pairs) {
  const auto n = static_cast<double>(s.radii.size());
  double q2 = 0, q3 = 0;  // mean (r_max / r_i)^2 and ^3
  for (Real ri : s.radii) q2 += std::pow(s.r_max / ri, 2), q3 += std::pow(s.r_max / ri, 3);
  state.counters["mean_square_ratio"] = q2 / n;
  state.counters["mean_cube_ratio"] = q3 / n;
  state.counters["pairs_per_particle"] = static_cast<double>(pairs) / n;
  state.counters["ns_per_particle"] =
      benchmark::Counter(n * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <class Search>
void build_2d(benchmark::State& state) {
  omp_set_num_threads(1);
  const Scene& s = scene_2d(static_cast<int>(state.range(0)));
  Search search(unit_square());
  NeighbourSearch<2> grid(unit_square());
  time_builds(state, search, grid, s.x, s.radii, s.r_max);
  counters_2d(state, s, search.list().pairs());
}
void BM_Grid2D(benchmark::State& state) { build_2d<NeighbourSearch<2>>(state); }
void BM_KdTree2D(benchmark::State& state) { build_2d<KdTreeNeighbourSearch<2>>(state); }

}  // namespace

BENCHMARK(BM_Grid2D)->ArgNames({"scene"})->DenseRange(0, kScenes2D - 1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KdTree2D)->ArgNames({"scene"})->DenseRange(0, kScenes2D - 1)->Unit(benchmark::kMillisecond);

// serial (nanoflann's search is called serially here; the grid and the tree also on 2 threads)
BENCHMARK(BM_Grid)->ArgNames({"scene", "threads"})->ArgsProduct({benchmark::CreateDenseRange(0, kScenes - 1, 1), {1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KdTree)->ArgNames({"scene", "threads"})->ArgsProduct({benchmark::CreateDenseRange(0, kScenes - 1, 1), {1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Nanoflann)->ArgNames({"scene"})->DenseRange(0, kScenes - 1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Grid)->ArgNames({"scene", "threads"})->ArgsProduct({{0, 4, 8}, {2}})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KdTree)->ArgNames({"scene", "threads"})->ArgsProduct({{0, 4, 8}, {2}})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
