// RCB decomposition: every rank gets the same tree; the domains tile space (each point in
// exactly one domain, that of its owner); the weight per domain is balanced to the requested
// tolerance; ranks_within finds the owner of every point within r (periodic images included).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "mpi_env.hpp"
#include "particles.hpp"
#include "sphark/parallel/decomposition.hpp"
#include "virtual_rcb.hpp"

namespace sphark {
namespace {

using testing::world;

// Every rank partitions its share (particles i with i % P == rank) of the same global set.
template <int D>
Decomposition<D> partition_share(const testing::GlobalParticles<D>& g, const std::vector<Real>& w,
                                 const std::optional<PeriodicBox<D>>& box, RcbStats* stats) {
  std::vector<Real> x, weights;
  for (std::size_t i = world().rank(); i < g.size(); i += world().size()) {
    for (int k = 0; k < D; ++k) x.push_back(g.x[D * i + k]);
    weights.push_back(w[i]);
  }
  return partition_rcb<D>(world(), x.data(), weights.data(), weights.size(), box, RcbOptions{}, stats);
}

// The same cuts on every rank: min and max over the ranks of every cut agree.
template <int D>
void expect_same_tree(const Decomposition<D>& dec) {
  std::vector<double> cuts;
  for (const auto& node : dec.tree()) cuts.push_back(node.axis >= 0 ? node.cut : -1.0);
  std::vector<double> lo = cuts, hi = cuts;
  world().allreduce(lo.data(), lo.size(), ReduceOp::Min);
  world().allreduce(hi.data(), hi.size(), ReduceOp::Max);
  EXPECT_EQ(lo, hi);
}

template <int D>
void check_partition(bool periodic, bool weighted) {
  const auto g = testing::make_particles<D>(6000, false, 0.05, 11);
  std::vector<Real> w(g.size(), 1.0);
  if (weighted)
    for (std::size_t i = 0; i < g.size(); ++i) w[i] = g.x[D * i] > 0.7 ? 10.0 : 1.0;  // a costly slab
  const auto box = testing::unit_box<D>(periodic);
  RcbStats stats;
  const Decomposition<D> dec = partition_share<D>(g, w, box, &stats);
  ASSERT_EQ(dec.ranks(), world().size());
  expect_same_tree(dec);
  // Weight per domain from the global set: within 1 % of the mean, and the reported imbalance.
  std::vector<Real> load(world().size(), 0.0);
  std::size_t outside = 0;
  for (std::size_t i = 0; i < g.size(); ++i) {
    const int owner = dec.owner(g.position(i));
    load[owner] += w[i];
    const auto& d = dec.domains()[owner];
    for (int k = 0; k < D; ++k) outside += (g.x[D * i + k] < d.lo[k] || g.x[D * i + k] >= d.hi[k]) ? 1 : 0;
  }
  EXPECT_EQ(outside, 0u);
  const Real total = std::accumulate(load.begin(), load.end(), 0.0);
  const Real worst = *std::max_element(load.begin(), load.end()) * world().size() / total;
  EXPECT_LE(worst, 1.01);
  EXPECT_NEAR(stats.imbalance, worst, 1e-12);
}

TEST(Decomposition, Balanced2DOpen) { check_partition<2>(false, false); }
TEST(Decomposition, Balanced3DPeriodic) { check_partition<3>(true, false); }
TEST(Decomposition, BalancedByWeight2D) { check_partition<2>(false, true); }

// Random points everywhere (also far outside the particles' region, and unwrapped images):
// exactly one domain contains each wrapped point, and it is the owner's.
TEST(Decomposition, DomainsTileSpace) {
  for (bool periodic : {false, true}) {
    const auto g = testing::make_particles<2>(3000, false, 0.05, 5);
    const auto box = testing::unit_box<2>(periodic);
    const Decomposition<2> dec = partition_share<2>(g, std::vector<Real>(g.size(), 1.0), box, nullptr);
    std::mt19937_64 gen(3);
    std::uniform_real_distribution<Real> u(-2, 3);
    std::size_t bad = 0;
    for (int s = 0; s < 20000; ++s) {
      const Vec<2> p(u(gen), u(gen));
      const Vec<2> q = box ? box->wrap(p) : p;
      int containing = 0, which = -1;
      for (int r = 0; r < dec.ranks(); ++r) {
        const auto& d = dec.domains()[r];
        if ((q.array() >= d.lo.array()).all() && (q.array() < d.hi.array()).all()) ++containing, which = r;
      }
      bad += (containing != 1 || which != dec.owner(p)) ? 1 : 0;
    }
    EXPECT_EQ(bad, 0u) << "periodic " << periodic;
  }
}

// For random pairs closer than r (minimum image), the owner of one is among the ranks within r
// of the other: what a halo needs.
TEST(Decomposition, RanksWithinFindTheOwnersOfNearbyPoints) {
  for (bool periodic : {false, true}) {
    const auto g = testing::make_particles<3>(4000, false, 0.05, 8);
    const auto box = testing::unit_box<3>(periodic);
    const Decomposition<3> dec = partition_share<3>(g, std::vector<Real>(g.size(), 1.0), box, nullptr);
    std::mt19937_64 gen(4);
    std::uniform_real_distribution<Real> u(0, 1), d(-0.1, 0.1);
    std::size_t missed = 0;
    std::vector<int> near;
    for (int s = 0; s < 20000; ++s) {
      const Vec<3> p(u(gen), u(gen), u(gen)), q = p + Vec<3>(d(gen), d(gen), d(gen));
      near.clear();
      dec.ranks_within(p, 0.1 * std::sqrt(3.0) + 1e-12, near);
      missed += std::binary_search(near.begin(), near.end(), dec.owner(q)) ? 0 : 1;
    }
    EXPECT_EQ(missed, 0u) << "periodic " << periodic;
  }
}

// The tree descent returns exactly the ranks the test of every domain and image returns: 1 to
// 1,000 virtual ranks, open and periodic boxes, radii from a hundredth to a half of the box.
TEST(Decomposition, RanksWithinByTheTreeEqualsEveryDomainTested) {
  std::mt19937_64 gen(11);
  std::uniform_real_distribution<Real> u(-0.2, 1.2), radius(0.01, 0.5);
  std::size_t mismatches = 0, found = 0;
  for (bool periodic : {false, true})
    for (int P : {1, 2, 3, 7, 64, 1000}) {
      Decomposition<3> dec(testing::unit_box<3>(periodic));
      std::vector<Decomposition<3>::Node> nodes;
      testing::virtual_tree<3>(0, P, Vec<3>::Zero(), Vec<3>::Ones(), nodes);
      dec.set_tree(nodes);
      std::vector<int> near;
      for (int s = 0; s < 2000; ++s) {
        const Vec<3> p(u(gen), u(gen), u(gen));
        const Real r = radius(gen);
        near.clear();
        dec.ranks_within(p, r, near);
        mismatches += near != testing::every_domain_within(dec, p, r);
        found += near.size();
      }
    }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GT(found, 24000u);  // not vacuous: most queries find several ranks
}

TEST(Decomposition, SerialCommunicatorGivesOneDomain) {
  const auto g = testing::make_particles<2>(100, true, 0.05, 1);
  const Decomposition<2> dec = partition_rcb<2>(Communicator{}, g.x.data(), nullptr, g.size(), std::nullopt);
  EXPECT_EQ(dec.ranks(), 1);
  EXPECT_EQ(dec.owner(Vec<2>(0.3, 7.0)), 0);
}

}  // namespace
}  // namespace sphark
