// Halo exchange: for random and lattice particles in 2D and 3D, periodic or not, with variable
// radii, the local + halo particles of every rank contain exactly (as a multiset of global ids)
// every particle b with |x_a - x_b| < max(r_a, r_b) of each local particle a: the serial
// brute-force list of the whole set. Halo values are the owners' bit for bit; a plan built with
// a skin stays exact while still_valid() says so.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>

#include "mpi_env.hpp"
#include "particles.hpp"
#include "sphark/parallel/decomposition.hpp"
#include "sphark/parallel/halo.hpp"

namespace sphark {
namespace {

using testing::world;

template <int D>
struct Part {  // this rank's particles (local first), positions, radii, ids
  std::vector<Real> x, r;
  std::vector<std::int64_t> ids;
};

// Local particles: those the RCB assigns to this rank, or (scattered) every P-th one: the halo
// must be right also for particles far from the rest of their rank's.
template <int D>
Part<D> local_part(const testing::GlobalParticles<D>& g, const std::optional<PeriodicBox<D>>& box, bool scattered) {
  const Decomposition<D> dec = partition_rcb<D>(world(), g.x.data(), nullptr, world().rank() == 0 ? g.size() : 0, box);
  Part<D> p;
  for (std::size_t i = 0; i < g.size(); ++i) {
    const bool mine = scattered ? int(i % world().size()) == world().rank() : dec.owner(g.position(i)) == world().rank();
    if (!mine) continue;
    for (int k = 0; k < D; ++k) p.x.push_back(g.x[D * i + k]);
    p.r.push_back(g.r[i]);
    p.ids.push_back(std::int64_t(i));
  }
  return p;
}

// Number of local particles whose neighbour multiset (by id) among local + halo differs from
// the brute-force one over the global set (positions gx: the current ones).
template <int D>
std::size_t mismatches(const std::vector<Real>& gx, const std::vector<Real>& gr, const Part<D>& p,
                       const HaloPlan<D>& plan, const std::vector<Real>& x_all, const std::vector<Real>& r_all,
                       const std::optional<PeriodicBox<D>>& box) {
  std::vector<std::int64_t> ids_all(p.ids);
  ids_all.insert(ids_all.end(), plan.halo_ids().begin(), plan.halo_ids().end());
  const std::size_t n = p.ids.size(), total = ids_all.size(), global = gr.size();
  std::size_t bad = 0;
  std::vector<std::int64_t> got, want;
  for (std::size_t a = 0; a < n; ++a) {
    got.clear();
    want.clear();
    const Vec<D> xa = Eigen::Map<const Vec<D>>(x_all.data() + D * a);
    for (std::size_t b = 0; b < total; ++b)
      if (b != a && testing::separation<D>(xa, Eigen::Map<const Vec<D>>(x_all.data() + D * b), box).norm() <
                        std::max(r_all[a], r_all[b]))
        got.push_back(ids_all[b]);
    const std::int64_t ia = p.ids[a];
    for (std::size_t j = 0; j < global; ++j)
      if (std::int64_t(j) != ia &&
          testing::separation<D>(Eigen::Map<const Vec<D>>(gx.data() + D * ia), Eigen::Map<const Vec<D>>(gx.data() + D * j), box)
                  .norm() < std::max(gr[ia], gr[j]))
        want.push_back(std::int64_t(j));
    std::sort(got.begin(), got.end());
    bad += got != want;
  }
  return bad;
}

template <int D>
void check_halo(bool lattice, bool periodic, bool scattered) {
  const auto g = testing::make_particles<D>(D == 2 ? 1600 : 1728, lattice, D == 2 ? 0.06 : 0.12, 31 + D);
  const auto box = testing::unit_box<D>(periodic);
  Part<D> p = local_part<D>(g, box, scattered);
  const std::size_t n = p.ids.size();
  HaloPlan<D> plan(world(), box);
  plan.build(p.x.data(), p.r.data(), p.ids.data(), n);
  std::vector<Real> x_all(p.x), r_all(p.r), tag(n);
  x_all.resize(D * (n + plan.halo()));
  r_all.resize(n + plan.halo());
  for (std::size_t a = 0; a < n; ++a) tag[a] = 0.5 + double(p.ids[a]);
  tag.resize(n + plan.halo());
  plan.exchange({{x_all.data(), D}, {r_all.data(), 1}});
  plan.exchange(tag.data(), 1);
  std::size_t wrong_values = 0, duplicates = 0;
  for (std::size_t k = 0; k < plan.halo(); ++k) {
    const std::int64_t id = plan.halo_ids()[k];
    for (int c = 0; c < D; ++c)
      wrong_values += std::bit_cast<std::uint64_t>(x_all[D * (n + k) + c]) != std::bit_cast<std::uint64_t>(g.x[D * id + c]);
    wrong_values += r_all[n + k] != g.r[id] || tag[n + k] != 0.5 + double(id);
  }
  std::vector<std::int64_t> ids(p.ids);
  ids.insert(ids.end(), plan.halo_ids().begin(), plan.halo_ids().end());
  std::sort(ids.begin(), ids.end());
  duplicates = static_cast<std::size_t>(ids.end() - std::unique(ids.begin(), ids.end()));
  const std::size_t bad = mismatches<D>(g.x, g.r, p, plan, x_all, r_all, box);
  EXPECT_EQ(testing::global_sum(std::int64_t(bad)), 0) << "lattice " << lattice << " periodic " << periodic;
  EXPECT_EQ(testing::global_sum(std::int64_t(wrong_values)), 0);
  EXPECT_EQ(testing::global_sum(std::int64_t(duplicates)), 0);
  const std::int64_t halo_total = testing::global_sum(std::int64_t(plan.halo()));
  if (world().size() > 1) {
    EXPECT_GT(halo_total, 0);
  }
}

TEST(Halo, Random2DOpen) { check_halo<2>(false, false, false); }
TEST(Halo, Random2DPeriodic) { check_halo<2>(false, true, false); }
TEST(Halo, Lattice2DPeriodic) { check_halo<2>(true, true, false); }
TEST(Halo, Lattice2DOpen) { check_halo<2>(true, false, false); }
TEST(Halo, Random3DOpen) { check_halo<3>(false, false, false); }
TEST(Halo, Random3DPeriodic) { check_halo<3>(false, true, false); }
TEST(Halo, Lattice3DPeriodic) { check_halo<3>(true, true, false); }
TEST(Halo, Lattice3DOpen) { check_halo<3>(true, false, false); }
TEST(Halo, ScatteredOwnership2DPeriodic) { check_halo<2>(false, true, true); }

// Domains cut for the positions, then every particle moved by 0.03 +- 0.01 along x and y (the
// state's coordinates, not wrapped: some pass 1): each rank's particles straddle its cuts and,
// for the last slabs, the periodic faces. The halo stays exact and compact (its coordinates are taken past
// the face, compact_periodic_coordinates): at most 1.5 times that of the unmoved domains, where
// a bounding box of the wrapped coordinates would take the whole period.
TEST(Halo, DomainsStraddlingThePeriodicFaceStayCompact) {
  const auto g = testing::make_particles<2>(1600, true, 0.04, 11);
  const auto box = testing::unit_box<2>(true);
  Part<2> p = local_part<2>(g, box, false);
  const std::size_t n = p.ids.size();
  HaloPlan<2> before(world(), box);
  before.build(p.x.data(), p.r.data(), p.ids.data(), n);
  auto moved = g;
  for (std::size_t i = 0; i < 2 * g.size(); ++i) moved.x[i] += 0.03 + 0.01 * std::sin(7.1 * double(i));
  for (std::size_t a = 0; a < n; ++a) p.x[2 * a] = moved.x[2 * p.ids[a]], p.x[2 * a + 1] = moved.x[2 * p.ids[a] + 1];
  HaloPlan<2> plan(world(), box);
  plan.build(p.x.data(), p.r.data(), p.ids.data(), n);
  std::vector<Real> x_all(p.x), r_all(p.r);
  x_all.resize(2 * (n + plan.halo()));
  r_all.resize(n + plan.halo());
  plan.exchange({{x_all.data(), 2}, {r_all.data(), 1}});
  EXPECT_EQ(testing::global_sum(std::int64_t(mismatches<2>(moved.x, moved.r, p, plan, x_all, r_all, box))), 0);
  const std::int64_t unmoved = testing::global_sum(std::int64_t(before.halo()));
  const std::int64_t straddling = testing::global_sum(std::int64_t(plan.halo()));
  EXPECT_LE(2 * straddling, 3 * unmoved) << "halo " << straddling << " particles, unmoved " << unmoved;
}

// Built with a skin, the plan stays exact for moved particles and grown radii while
// still_valid() holds; beyond that still_valid() is false on every rank.
TEST(Halo, SkinKeepsThePlanExactWhileValid) {
  const auto g = testing::make_particles<2>(1600, false, 0.05, 77);
  const auto box = testing::unit_box<2>(true);
  Part<2> p = local_part<2>(g, box, false);
  const std::size_t n = p.ids.size();
  const Real skin = 0.02;
  HaloPlan<2> plan(world(), box);
  plan.build(p.x.data(), p.r.data(), p.ids.data(), n, skin);
  // Move every particle by 0.4 skin / 2 in a direction of its own, grow radii by 0.1 skin.
  auto moved = g;
  for (std::size_t i = 0; i < g.size(); ++i) {
    const Real angle = 2.399963 * double(i);
    moved.x[2 * i] += 0.4 * skin * std::cos(angle);
    moved.x[2 * i + 1] += 0.4 * skin * std::sin(angle);
    moved.r[i] += 0.1 * skin;
  }
  for (std::size_t a = 0; a < n; ++a) {
    p.x[2 * a] = moved.x[2 * p.ids[a]], p.x[2 * a + 1] = moved.x[2 * p.ids[a] + 1];
    p.r[a] = moved.r[p.ids[a]];
  }
  EXPECT_TRUE(plan.still_valid(p.x.data(), p.r.data()));  // 2 (0.4 skin) + 0.1 skin <= skin
  std::vector<Real> x_all(p.x), r_all(p.r);
  x_all.resize(2 * (n + plan.halo()));
  r_all.resize(n + plan.halo());
  plan.exchange({{x_all.data(), 2}, {r_all.data(), 1}});
  EXPECT_EQ(testing::global_sum(std::int64_t(mismatches<2>(moved.x, moved.r, p, plan, x_all, r_all, box))), 0);
  if (world().rank() == world().size() - 1 && n > 0) p.x[0] += skin;  // one particle on one rank, now >= 0.6 skin from its start
  EXPECT_FALSE(plan.still_valid(p.x.data(), p.r.data()));
}

TEST(Halo, TooSmallPeriodicBoxFailsOnEveryRank) {
  const auto g = testing::make_particles<2>(400, false, 0.5, 5);  // r up to 0.7 > L / 2
  const auto box = testing::unit_box<2>(true);
  Part<2> p = local_part<2>(g, box, false);
  HaloPlan<2> plan(world(), box);
  EXPECT_THROW(plan.build(p.x.data(), p.r.data(), p.ids.data(), p.ids.size()), CollectiveError);
}

}  // namespace
}  // namespace sphark
