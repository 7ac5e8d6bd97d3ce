// Costs of the distributed infrastructure (docs/scaling.md), total particle counts N over the
// ranks, uniform random in the unit cube (3D):
//   Rcb/N             partition_rcb (weights 1); counter imbalance = max / mean weight
//   Owners/N          Decomposition::owners of every local particle
//   Migrate/N         migrate from a random assignment to the RCB domains (x, v, m, h; about
//                     (P-1)/P of the particles move)
//   HaloBuild/N       HaloPlan::build (r = 2h, h = 1.2 N^(-1/3): ~58 neighbours), periodic box
//   HaloExchange/N    one exchange of x and v (6 values per halo particle); counters: halo per
//                     rank, bytes and messages per rank per exchange
//   Allreduce         one double (MPI_Allreduce sum), and the 8 int64 of the reproducible norm
//   Wrms/N            ARKODE's WRMS norm of an N-entry parallel vector: SUNDIALS' and ours
// Run: mpirun --oversubscribe --allow-run-as-root -np P build/bin/bench_mpi_distributed
#include <cmath>
#include <random>

#include <nvector/nvector_serial.h>

#include "../virtual_rcb.hpp"
#include "bench_support.hpp"
#include "sphark/parallel/decomposition.hpp"
#include "sphark/parallel/halo.hpp"
#include "sphark/parallel/migration.hpp"
#include "sphark/parallel/sundials_vector.hpp"

namespace sphark::bench {
namespace {

std::optional<PeriodicBox<3>> unit_box() {
  PeriodicBox<3> b;
  b.periodic = {true, true, true};
  return b;
}

void Rcb(benchmark::State& state) {
  const auto x = random_points<3>(local_share(state.range(0)));
  RcbStats stats;
  for (auto _ : state) timed(state, [&] { partition_rcb<3>(world(), x.data(), nullptr, x.size() / 3, unit_box(), {}, &stats); });
  state.counters["imbalance"] = stats.imbalance;
  state.counters["refinements"] = stats.refinements;
}

void Owners(benchmark::State& state) {
  const auto x = random_points<3>(local_share(state.range(0)));
  const auto dec = partition_rcb<3>(world(), x.data(), nullptr, x.size() / 3, unit_box());
  std::vector<int> owner(x.size() / 3);
  for (auto _ : state) timed(state, [&] { dec.owners(x.data(), owner.size(), owner.data()); });
}

void Migrate(benchmark::State& state) {
  const std::size_t n = local_share(state.range(0));
  const auto x0 = random_points<3>(n);
  const auto dec = partition_rcb<3>(world(), x0.data(), nullptr, n, unit_box());
  std::size_t sent = 0;
  for (auto _ : state) {
    std::vector<Real> x = x0, v(3 * n, 1.0), m(n, 1.0), h(n, 0.01);
    std::vector<std::int64_t> ids(n);
    for (std::size_t i = 0; i < n; ++i) ids[i] = std::int64_t(world().rank() * n + i);
    std::vector<int> owner(n);
    dec.owners(x.data(), n, owner.data());
    ParticleData d;
    d.ids = &ids;
    d.arrays = {{&x, 3}, {&v, 3}, {&m, 1}, {&h, 1}};
    d.mass.array = 2;
    d.velocity.array = 1;
    d.dim = 3;
    timed(state, [&] { sent = migrate(world(), owner, d).sent; });
  }
  state.counters["sent_per_rank"] = double(sent);
}

// Particles of this rank inside its RCB domain (a migration first), radius 2h.
struct Domain {
  std::vector<Real> x, r;
  std::vector<std::int64_t> ids;
};
Domain domain(std::size_t total) {
  const std::size_t n = local_share(total);
  Domain d{random_points<3>(n), {}, {}};
  for (std::size_t i = 0; i < n; ++i) d.ids.push_back(std::int64_t(world().rank() * n + i));
  const auto dec = partition_rcb<3>(world(), d.x.data(), nullptr, n, unit_box());
  std::vector<int> owner(n);
  dec.owners(d.x.data(), n, owner.data());
  ParticleData pd;
  pd.ids = &d.ids;
  pd.arrays = {{&d.x, 3}};
  migrate(world(), owner, pd);
  d.r.assign(d.ids.size(), 2 * 1.2 * std::cbrt(1.0 / double(total)));
  return d;
}

void HaloBuild(benchmark::State& state) {
  const Domain d = domain(state.range(0));
  HaloPlan<3> plan(world(), unit_box());
  for (auto _ : state) timed(state, [&] { plan.build(d.x.data(), d.r.data(), d.ids.data(), d.ids.size()); });
  state.counters["halo_per_rank"] = double(plan.halo());
}

void HaloExchange(benchmark::State& state) {
  const Domain d = domain(state.range(0));
  HaloPlan<3> plan(world(), unit_box());
  plan.build(d.x.data(), d.r.data(), d.ids.data(), d.ids.size());
  std::vector<Real> x = d.x, v(d.x.size(), 1.0);
  x.resize(3 * (d.ids.size() + plan.halo()));
  v.resize(x.size());
  for (auto _ : state) timed(state, [&] { plan.exchange({{x.data(), 3}, {v.data(), 3}}); });
  state.counters["halo_per_rank"] = double(plan.halo());
  state.counters["halo_fraction"] = double(plan.halo()) / double(d.ids.size());
  state.counters["bytes_per_rank"] = double(plan.stats().sent * 6 * sizeof(Real));
  state.counters["messages_per_rank"] = double(plan.stats().send_partners);
}

void Allreduce(benchmark::State& state) {
  double v = 1;
  std::int64_t limbs[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  for (auto _ : state)
    timed(state, [&] {
      if (state.range(0) == 1) v = world().allreduce(v, ReduceOp::Sum);
      else world().allreduce(limbs, 8, ReduceOp::Sum);
    });
}

void Wrms(benchmark::State& state) {
  const std::size_t n = local_share(state.range(0));
  SUNContext ctx = nullptr;
  create_sundials_context(world(), &ctx);
  std::vector<Real> x = random_points<1>(n), w(n, 1e3);
  N_Vector vx = make_vector_view(world(), n, x.data(), ctx), vw = make_vector_view(world(), n, w.data(), ctx);
  if (state.range(1) == 1) make_norms_reproducible(vx);
  double norm = 0;
  for (auto _ : state) timed(state, [&] { norm = N_VWrmsNorm(vx, vw); });
  benchmark::DoNotOptimize(norm);
  N_VDestroy(vx);
  N_VDestroy(vw);
  SUNContext_Free(&ctx);
}

// ranks_within at P virtual ranks (a balanced tree over the periodic unit cube; no MPI): the tree
// descent (arg 1 = 0) against testing every domain and image (arg 1 = 1), per query; radius of a
// halo at 10^5 particles per rank, 2 x 1.2 x 1.3 x (P 10^5)^(-1/3).
void RanksWithin(benchmark::State& state) {
  const int P = static_cast<int>(state.range(0));
  Decomposition<3> dec(unit_box());
  std::vector<Decomposition<3>::Node> nodes;
  testing::virtual_tree<3>(0, P, Vec<3>::Zero(), Vec<3>::Ones(), nodes);
  dec.set_tree(nodes);
  const Real r = 2 * 1.2 * 1.3 * std::cbrt(1.0 / (double(P) * 1e5));
  std::mt19937_64 gen(5);
  std::uniform_real_distribution<Real> u(0, 1);
  std::vector<int> near;
  std::size_t found = 0, queries = 0;
  for (auto _ : state) {
    const Vec<3> p(u(gen), u(gen), u(gen));
    if (state.range(1) == 0) {
      near.clear();
      dec.ranks_within(p, r, near);
      found += near.size();
    } else {
      found += testing::every_domain_within(dec, p, r).size();
    }
    ++queries;
  }
  state.counters["ranks_found"] = double(found) / double(std::max<std::size_t>(queries, 1));
}

BENCHMARK(Rcb)->Arg(100000)->Arg(1000000)->Iterations(5)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(Owners)->Arg(100000)->Arg(1000000)->Iterations(5)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(Migrate)->Arg(100000)->Arg(1000000)->Iterations(3)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(HaloBuild)->Arg(100000)->Iterations(5)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(HaloExchange)->Arg(10000)->Arg(100000)->Arg(1000000)->Iterations(50)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(Allreduce)->Arg(1)->Arg(8)->Iterations(2000)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(RanksWithin)->ArgsProduct({{8, 64, 1000, 10000}, {0, 1}})->Unit(benchmark::kMicrosecond);
BENCHMARK(Wrms)->Args({100000, 0})->Args({100000, 1})->Iterations(200)->UseManualTime()->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace sphark::bench

SPHARK_MPI_BENCH_MAIN()
