#pragma once
// The ranks of a distributed run, and every collective the code needs, behind one small type.
//
// A default-constructed Communicator is the serial one: one rank, no MPI call ever (so the
// serial code paths need no #if and are bit-identical whether or not MPI is built). A
// Communicator backed by MPI comes from MpiSession::world() (parallel/mpi_session.hpp) and wraps
// a duplicate of MPI_COMM_WORLD, so our messages never meet a caller's.
//
// Errors. Every collective must be reached by every rank. A failure that one rank detects is
// made collective with check() / agree() / collectively(): every rank learns of it (with the
// failing ranks' messages, "rank r: ...") and throws or returns the same thing, so all ranks end
// the same way. A rank that fails where the others cannot be told (an exception escaping between
// collectives) ends the run through MpiSession's handler with MPI_Abort (the last resort), and a
// point-to-point exchange that waits longer than SPHARK_MPI_TIMEOUT seconds (default 600) for a
// partner aborts with a message instead of hanging.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace sphark {

enum class ReduceOp { Sum, Min, Max };

// Thrown on every rank at once by the collective checks, with the failing ranks' messages.
class CollectiveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace detail {
struct MpiComm;  // the MPI_Comm, defined in src/parallel/mpi_backend.cpp only
}

class Communicator {
 public:
  Communicator() = default;  // serial: one rank, no MPI
  explicit Communicator(std::shared_ptr<const detail::MpiComm> mpi);

  int rank() const { return rank_; }
  int size() const { return size_; }
  // Backed by MPI (also with one rank: the steppers then use SUNDIALS' parallel vectors).
  bool distributed() const { return mpi_ != nullptr; }
  // Pointer to the MPI_Comm (for SUNContext_Create); nullptr when serial.
  const void* mpi_handle() const;
  // The MPI side, for src/parallel only; nullptr when serial.
  const detail::MpiComm* backend() const { return mpi_.get(); }

  void barrier() const;

  // In-place reductions of n values over all ranks.
  void allreduce(double* values, std::size_t n, ReduceOp op) const;
  void allreduce(std::int64_t* values, std::size_t n, ReduceOp op) const;
  double allreduce(double value, ReduceOp op) const;
  std::int64_t allreduce(std::int64_t value, ReduceOp op) const;

  // all[r * n + k] = rank r's mine[k] (every rank gives n values).
  std::vector<double> allgather(const double* mine, std::size_t n) const;
  std::vector<std::int64_t> allgather(const std::int64_t* mine, std::size_t n) const;
  // received[r] = what rank r put at send[this rank] (one value per rank pair).
  std::vector<std::int64_t> alltoall(const std::vector<std::int64_t>& send) const;

  // Point-to-point messages with known partners, all posted at once and completed before the
  // call returns (a message to this rank itself is a copy). Collective over the partners.
  struct Send {
    int rank;
    const void* data;
    std::size_t bytes;
  };
  struct Receive {
    int rank;
    void* data;
    std::size_t bytes;
  };
  void exchange(const std::vector<Send>& sends, const std::vector<Receive>& receives) const;

  // Collective: "rank r: <message>" of every rank with a non-empty message, "; "-separated, in
  // rank order (the same string on every rank).
  std::string gather_messages(const std::string& mine) const;

  // Collective: if any rank passes ok = false, every rank throws CollectiveError with the
  // failing ranks' messages.
  void check(bool ok, const std::string& message) const;
  // Collective: the most severe of the ranks' return codes (0 ok, > 0 recoverable, < 0 fatal):
  // the smallest negative one, else the largest positive one, else 0. When it is not 0,
  // `message` becomes the gathered messages of the ranks whose code was not 0.
  int agree(int code, std::string& message) const;
  // Runs f() on every rank; if it throws on any rank, every rank throws CollectiveError with
  // the messages (the exception does not leave a rank alone).
  template <class F>
  void collectively(F&& f) const {
    std::string error;
    try {
      f();
    } catch (const std::exception& e) {
      error = e.what();
      if (error.empty()) error = "exception";
    } catch (...) {
      error = "unknown exception";
    }
    check(error.empty(), error);
  }

  // Ends every rank (MPI_Abort; std::abort when serial) after printing the message to stderr.
  [[noreturn]] void abort(int code, const std::string& message) const noexcept;

 private:
  std::shared_ptr<const detail::MpiComm> mpi_;
  int rank_ = 0, size_ = 1;
};

}  // namespace sphark
