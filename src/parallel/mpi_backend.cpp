// The one file that calls MPI (compiled with SPHARK_HAVE_MPI and mpi.h only when SPHARK_MPI is
// ON, see CMakeLists.txt). Without MPI the functions exist but are unreachable: no serial
// Communicator ever holds an MpiComm.
#include "mpi_backend.hpp"

#include <chrono>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <string>

#ifdef SPHARK_HAVE_MPI
#include <mpi.h>
#include <nvector/nvector_parallel.h>
#endif

namespace sphark::detail {

#ifdef SPHARK_HAVE_MPI

struct MpiComm {
  MPI_Comm comm = MPI_COMM_NULL;
  MpiComm() = default;
  MpiComm(const MpiComm&) = delete;
  ~MpiComm() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized && comm != MPI_COMM_NULL) MPI_Comm_free(&comm);
  }
};

namespace {

constexpr int kExchangeTag = 0x5a17;

MPI_Op mpi_op(ReduceOp op) {
  switch (op) {
    case ReduceOp::Sum: return MPI_SUM;
    case ReduceOp::Min: return MPI_MIN;
    case ReduceOp::Max: return MPI_MAX;
  }
  return MPI_SUM;
}

int count_of(std::size_t n, const char* what) {
  if (n > static_cast<std::size_t>(INT_MAX))
    throw std::length_error(std::string(what) + ": " + std::to_string(n) + " items exceed one MPI message");
  return static_cast<int>(n);
}

// SPHARK_MPI_TIMEOUT seconds (default 600) a point-to-point exchange may wait for its partners.
double exchange_timeout() {
  static const double seconds = [] {
    const char* env = std::getenv("SPHARK_MPI_TIMEOUT");
    const double v = env ? std::atof(env) : 0.0;
    return v > 0 ? v : 600.0;
  }();
  return seconds;
}

// MPI_Testall until done; after exchange_timeout() seconds, abort with a message (a partner
// that never posts its message has failed elsewhere: waiting on would hang the run).
void wait_all(const MpiComm& c, std::vector<MPI_Request>& requests) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  for (long polls = 0;; ++polls) {
    int done = 0;
    MPI_Testall(static_cast<int>(requests.size()), requests.data(), &done, MPI_STATUSES_IGNORE);
    if (done) return;
    if (polls % 4096 == 4095 && std::chrono::duration<double>(Clock::now() - start).count() > exchange_timeout()) {
      int rank = 0;
      MPI_Comm_rank(c.comm, &rank);
      std::fprintf(stderr, "rank %d: point-to-point exchange waited %.0f s (SPHARK_MPI_TIMEOUT) for its partners; "
                   "another rank has probably failed outside a collective check (aborting all ranks)\n",
                   rank, exchange_timeout());
      std::fflush(stderr);
      MPI_Abort(c.comm, 3);
    }
  }
}

}  // namespace

bool mpi_built() { return true; }

bool mpi_initialized() {
  int initialized = 0;
  MPI_Initialized(&initialized);
  return initialized != 0;
}

bool mpi_init(int& argc, char**& argv) {
  if (mpi_initialized()) return false;
  int provided = 0;
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    throw std::runtime_error("MPI_Init_thread failed");
  return true;
}

void mpi_finalize() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

std::shared_ptr<const MpiComm> mpi_world() {
  auto c = std::make_shared<MpiComm>();
  if (MPI_Comm_dup(MPI_COMM_WORLD, &c->comm) != MPI_SUCCESS) throw std::runtime_error("MPI_Comm_dup failed");
  return c;
}

int mpi_rank(const MpiComm& c) {
  int r = 0;
  MPI_Comm_rank(c.comm, &r);
  return r;
}
int mpi_size(const MpiComm& c) {
  int s = 1;
  MPI_Comm_size(c.comm, &s);
  return s;
}
const void* mpi_handle(const MpiComm& c) { return &c.comm; }
void mpi_barrier(const MpiComm& c) { MPI_Barrier(c.comm); }

void mpi_allreduce(const MpiComm& c, double* values, std::size_t n, ReduceOp op) {
  MPI_Allreduce(MPI_IN_PLACE, values, count_of(n, "allreduce"), MPI_DOUBLE, mpi_op(op), c.comm);
}
void mpi_allreduce(const MpiComm& c, std::int64_t* values, std::size_t n, ReduceOp op) {
  MPI_Allreduce(MPI_IN_PLACE, values, count_of(n, "allreduce"), MPI_INT64_T, mpi_op(op), c.comm);
}
void mpi_allgather(const MpiComm& c, const double* mine, std::size_t n, double* all) {
  const int k = count_of(n, "allgather");
  MPI_Allgather(mine, k, MPI_DOUBLE, all, k, MPI_DOUBLE, c.comm);
}
void mpi_allgather(const MpiComm& c, const std::int64_t* mine, std::size_t n, std::int64_t* all) {
  const int k = count_of(n, "allgather");
  MPI_Allgather(mine, k, MPI_INT64_T, all, k, MPI_INT64_T, c.comm);
}
void mpi_alltoall(const MpiComm& c, const std::int64_t* send, std::int64_t* received) {
  MPI_Alltoall(send, 1, MPI_INT64_T, received, 1, MPI_INT64_T, c.comm);
}

void mpi_exchange(const MpiComm& c, const std::vector<Communicator::Send>& sends,
                  const std::vector<Communicator::Receive>& receives) {
  const int self = mpi_rank(c);
  static thread_local std::vector<MPI_Request> requests;  // capacity kept: no allocation per exchange
  static thread_local std::vector<const Communicator::Send*> self_sends;
  requests.clear();
  self_sends.clear();
  for (const auto& r : receives) {
    if (r.rank == self) continue;
    requests.emplace_back();
    MPI_Irecv(r.data, count_of(r.bytes, "exchange"), MPI_BYTE, r.rank, kExchangeTag, c.comm, &requests.back());
  }
  for (const auto& s : sends) {
    if (s.rank == self) {
      self_sends.push_back(&s);
      continue;
    }
    requests.emplace_back();
    MPI_Isend(s.data, count_of(s.bytes, "exchange"), MPI_BYTE, s.rank, kExchangeTag, c.comm, &requests.back());
  }
  std::size_t k = 0;  // the k-th message to itself is the k-th receive from itself
  for (const auto& r : receives) {
    if (r.rank != self) continue;
    if (k >= self_sends.size() || self_sends[k]->bytes != r.bytes)
      throw std::logic_error("Communicator::exchange: messages to self do not match the receives from self");
    if (r.bytes > 0) std::memcpy(r.data, self_sends[k]->data, r.bytes);
    ++k;
  }
  if (k != self_sends.size()) throw std::logic_error("Communicator::exchange: unmatched message to self");
  wait_all(c, requests);
}

void mpi_abort(const MpiComm& c, int code) noexcept {
  MPI_Abort(c.comm, code);
  std::abort();
}

void raw_allreduce(void* comm, double* values, std::size_t n, ReduceOp op) {
  if (comm) MPI_Allreduce(MPI_IN_PLACE, values, count_of(n, "allreduce"), MPI_DOUBLE, mpi_op(op), *static_cast<MPI_Comm*>(comm));
}
void raw_allreduce(void* comm, std::int64_t* values, std::size_t n, ReduceOp op) {
  if (comm) MPI_Allreduce(MPI_IN_PLACE, values, count_of(n, "allreduce"), MPI_INT64_T, mpi_op(op), *static_cast<MPI_Comm*>(comm));
}
std::size_t parallel_local_length(N_Vector v) { return static_cast<std::size_t>(N_VGetLocalLength_Parallel(v)); }

N_Vector mpi_make_vector(const MpiComm& c, std::size_t local, double* data, SUNContext ctx) {
  long long global = static_cast<long long>(local);
  MPI_Allreduce(MPI_IN_PLACE, &global, 1, MPI_LONG_LONG, MPI_SUM, c.comm);
  return N_VMake_Parallel(c.comm, static_cast<sunindextype>(local), static_cast<sunindextype>(global), data, ctx);
}

#else  // built without MPI: never reached (a serial Communicator holds no MpiComm)

struct MpiComm {};

namespace {
[[noreturn]] void unreachable() { throw std::logic_error("sphark was built without MPI (SPHARK_MPI=OFF)"); }
}  // namespace

bool mpi_built() { return false; }
bool mpi_initialized() { return false; }
bool mpi_init(int&, char**&) { return false; }
void mpi_finalize() {}
std::shared_ptr<const MpiComm> mpi_world() { return nullptr; }
int mpi_rank(const MpiComm&) { unreachable(); }
int mpi_size(const MpiComm&) { unreachable(); }
const void* mpi_handle(const MpiComm&) { unreachable(); }
void mpi_barrier(const MpiComm&) { unreachable(); }
void mpi_allreduce(const MpiComm&, double*, std::size_t, ReduceOp) { unreachable(); }
void mpi_allreduce(const MpiComm&, std::int64_t*, std::size_t, ReduceOp) { unreachable(); }
void mpi_allgather(const MpiComm&, const double*, std::size_t, double*) { unreachable(); }
void mpi_allgather(const MpiComm&, const std::int64_t*, std::size_t, std::int64_t*) { unreachable(); }
void mpi_alltoall(const MpiComm&, const std::int64_t*, std::int64_t*) { unreachable(); }
void mpi_exchange(const MpiComm&, const std::vector<Communicator::Send>&, const std::vector<Communicator::Receive>&) {
  unreachable();
}
void mpi_abort(const MpiComm&, int) noexcept { std::abort(); }
void raw_allreduce(void* comm, double*, std::size_t, ReduceOp) {
  if (comm) unreachable();
}
void raw_allreduce(void* comm, std::int64_t*, std::size_t, ReduceOp) {
  if (comm) unreachable();
}
std::size_t parallel_local_length(N_Vector) { unreachable(); }
N_Vector mpi_make_vector(const MpiComm&, std::size_t, double*, SUNContext) { unreachable(); }

#endif

}  // namespace sphark::detail
