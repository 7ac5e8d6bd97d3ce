// Zoltan (Trilinos 13.2, Debian's libtrilinos-zoltan-dev) on the input of bench_mpi_distributed's
// Rcb/N and Owners/N, for the comparison in docs/scaling.md:
//   Zoltan/N/method   Zoltan_LB_Partition (RCB, RIB or HSFC, geometry by a multi-object
//                     callback, export lists); counter imbalance = max / mean particles after
//   ZoltanOwners/N    Zoltan_LB_Point_Assign for every local particle (RCB with KEEP_CUTS)
// Run: mpirun --oversubscribe --allow-run-as-root -np P build/bin/bench_mpi_zoltan_partition
#include <mpi.h>
#include <zoltan.h>

#include <algorithm>
#include <stdexcept>

#include "../bench_support.hpp"

namespace sphark::bench {
namespace {

struct Points {
  std::vector<Real> x;  // 3 per point
  std::size_t n() const { return x.size() / 3; }
};

int num_obj(void* data, int* ierr) {
  *ierr = ZOLTAN_OK;
  return static_cast<int>(static_cast<Points*>(data)->n());
}
void obj_list(void* data, int, int, ZOLTAN_ID_PTR gids, ZOLTAN_ID_PTR lids, int, float*, int* ierr) {
  const auto* p = static_cast<Points*>(data);
  const auto offset = static_cast<ZOLTAN_ID_TYPE>(world().rank() * p->n());
  for (std::size_t i = 0; i < p->n(); ++i) gids[i] = offset + static_cast<ZOLTAN_ID_TYPE>(i), lids[i] = static_cast<ZOLTAN_ID_TYPE>(i);
  *ierr = ZOLTAN_OK;
}
int num_geom(void*, int* ierr) {
  *ierr = ZOLTAN_OK;
  return 3;
}
void geom_multi(void* data, int, int, int num, ZOLTAN_ID_PTR, ZOLTAN_ID_PTR lids, int, double* geom, int* ierr) {
  const auto* p = static_cast<Points*>(data);
  for (int k = 0; k < num; ++k) std::copy_n(p->x.data() + 3 * lids[k], 3, geom + 3 * k);
  *ierr = ZOLTAN_OK;
}

// A configured Zoltan_Struct over the points (RAII).
struct Zoltan {
  Zoltan_Struct* zz;
  Zoltan(Points& p, const char* method) : zz((initialize(), Zoltan_Create(*static_cast<const MPI_Comm*>(world().mpi_handle())))) {
    Zoltan_Set_Param(zz, "DEBUG_LEVEL", "0");
    Zoltan_Set_Param(zz, "IMBALANCE_TOL", "1.001");  // as partition_rcb's default tolerance (1e-3)
    Zoltan_Set_Param(zz, "LB_METHOD", method);
    Zoltan_Set_Param(zz, "NUM_GID_ENTRIES", "1");
    Zoltan_Set_Param(zz, "NUM_LID_ENTRIES", "1");
    Zoltan_Set_Param(zz, "RETURN_LISTS", "EXPORT");
    Zoltan_Set_Param(zz, "KEEP_CUTS", "1");
    Zoltan_Set_Num_Obj_Fn(zz, num_obj, &p);
    Zoltan_Set_Obj_List_Fn(zz, obj_list, &p);
    Zoltan_Set_Num_Geom_Fn(zz, num_geom, &p);
    Zoltan_Set_Geom_Multi_Fn(zz, geom_multi, &p);
  }
  ~Zoltan() { Zoltan_Destroy(&zz); }
  static void initialize() {
    static const bool once = [] {
      float version = 0;
      return Zoltan_Initialize(0, nullptr, &version) == ZOLTAN_OK;
    }();
    if (!once) throw std::runtime_error("Zoltan_Initialize failed");
  }
  // Partitions; returns the number of particles this rank exports.
  int partition() {
    int changes, ngid, nlid, nimp, nexp;
    ZOLTAN_ID_PTR igid, ilid, egid, elid;
    int *iproc, *ipart, *eproc, *epart;
    if (Zoltan_LB_Partition(zz, &changes, &ngid, &nlid, &nimp, &igid, &ilid, &iproc, &ipart, &nexp, &egid, &elid,
                            &eproc, &epart) != ZOLTAN_OK)
      throw std::runtime_error("Zoltan_LB_Partition failed");
    Zoltan_LB_Free_Part(&igid, &ilid, &iproc, &ipart);
    Zoltan_LB_Free_Part(&egid, &elid, &eproc, &epart);
    return nexp;
  }
};

const char* kMethods[] = {"RCB", "RIB", "HSFC"};

void ZoltanLb(benchmark::State& state) {
  Points p{random_points<3>(local_share(state.range(0)))};
  Zoltan z(p, kMethods[state.range(1)]);
  std::int64_t exported = 0;
  for (auto _ : state) timed(state, [&] { exported = z.partition(); });
  // The ranks' particle counts after (without moving them): exports only leave, imports arrive.
  std::vector<int> owner(p.n());
  for (std::size_t i = 0; i < p.n(); ++i) Zoltan_LB_Point_Assign(z.zz, p.x.data() + 3 * i, &owner[i]);
  std::vector<Real> count(world().size(), 0.0);
  for (int o : owner) count[o] += 1;
  world().allreduce(count.data(), count.size(), ReduceOp::Sum);
  const Real mean = double(state.range(0)) / world().size();
  state.counters["imbalance"] = *std::max_element(count.begin(), count.end()) / mean;
  state.counters["exported_per_rank"] = double(exported);
  state.SetLabel(kMethods[state.range(1)]);
}

void ZoltanOwners(benchmark::State& state) {
  Points p{random_points<3>(local_share(state.range(0)))};
  Zoltan z(p, "RCB");
  z.partition();
  std::vector<int> owner(p.n());
  for (auto _ : state)
    timed(state, [&] {
      for (std::size_t i = 0; i < p.n(); ++i) Zoltan_LB_Point_Assign(z.zz, p.x.data() + 3 * i, &owner[i]);
    });
}

BENCHMARK(ZoltanLb)->ArgsProduct({{100000, 1000000}, {0, 1, 2}})->Iterations(5)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(ZoltanOwners)->Arg(100000)->Arg(1000000)->Iterations(5)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sphark::bench

SPHARK_MPI_BENCH_MAIN()
