// Communicator: the serial behaviour (one rank) here, the MPI calls in mpi_backend.cpp.
#include "sphark/parallel/communicator.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "mpi_backend.hpp"

namespace sphark {

Communicator::Communicator(std::shared_ptr<const detail::MpiComm> mpi) : mpi_(std::move(mpi)) {
  if (mpi_) {
    rank_ = detail::mpi_rank(*mpi_);
    size_ = detail::mpi_size(*mpi_);
  }
}

const void* Communicator::mpi_handle() const { return mpi_ ? detail::mpi_handle(*mpi_) : nullptr; }

void Communicator::barrier() const {
  if (mpi_) detail::mpi_barrier(*mpi_);
}

void Communicator::allreduce(double* values, std::size_t n, ReduceOp op) const {
  if (mpi_) detail::mpi_allreduce(*mpi_, values, n, op);
}
void Communicator::allreduce(std::int64_t* values, std::size_t n, ReduceOp op) const {
  if (mpi_) detail::mpi_allreduce(*mpi_, values, n, op);
}
double Communicator::allreduce(double value, ReduceOp op) const {
  allreduce(&value, 1, op);
  return value;
}
std::int64_t Communicator::allreduce(std::int64_t value, ReduceOp op) const {
  allreduce(&value, 1, op);
  return value;
}

std::vector<double> Communicator::allgather(const double* mine, std::size_t n) const {
  std::vector<double> all(n * static_cast<std::size_t>(size_));
  if (mpi_) detail::mpi_allgather(*mpi_, mine, n, all.data());
  else std::copy(mine, mine + n, all.begin());
  return all;
}
std::vector<std::int64_t> Communicator::allgather(const std::int64_t* mine, std::size_t n) const {
  std::vector<std::int64_t> all(n * static_cast<std::size_t>(size_));
  if (mpi_) detail::mpi_allgather(*mpi_, mine, n, all.data());
  else std::copy(mine, mine + n, all.begin());
  return all;
}

std::vector<std::int64_t> Communicator::alltoall(const std::vector<std::int64_t>& send) const {
  if (send.size() != static_cast<std::size_t>(size_))
    throw std::invalid_argument("Communicator::alltoall: " + std::to_string(send.size()) +
                                " values for " + std::to_string(size_) + " ranks");
  std::vector<std::int64_t> received(send.size());
  if (mpi_) detail::mpi_alltoall(*mpi_, send.data(), received.data());
  else received = send;
  return received;
}

void Communicator::exchange(const std::vector<Send>& sends, const std::vector<Receive>& receives) const {
  for (const Send& s : sends)
    if (s.rank < 0 || s.rank >= size_) throw std::invalid_argument("Communicator::exchange: bad rank " + std::to_string(s.rank));
  for (const Receive& r : receives)
    if (r.rank < 0 || r.rank >= size_) throw std::invalid_argument("Communicator::exchange: bad rank " + std::to_string(r.rank));
  if (mpi_) return detail::mpi_exchange(*mpi_, sends, receives);
  if (sends.size() != receives.size())
    throw std::logic_error("Communicator::exchange (serial): " + std::to_string(sends.size()) + " sends, " +
                           std::to_string(receives.size()) + " receives");
  for (std::size_t k = 0; k < sends.size(); ++k) {
    if (sends[k].bytes != receives[k].bytes) throw std::logic_error("Communicator::exchange (serial): size mismatch");
    if (sends[k].bytes > 0) std::memcpy(receives[k].data, sends[k].data, sends[k].bytes);
  }
}

std::string Communicator::gather_messages(const std::string& mine) const {
  if (!mpi_) return mine.empty() ? mine : "rank 0: " + mine;
  const std::int64_t length = static_cast<std::int64_t>(mine.size());
  const std::vector<std::int64_t> lengths = allgather(&length, 1);
  std::int64_t longest = *std::max_element(lengths.begin(), lengths.end());
  if (longest == 0) return {};
  // Fixed-width slots (the messages are short; this is the failure path).
  std::vector<double> slot(static_cast<std::size_t>((longest + 7) / 8), 0.0);
  std::memcpy(slot.data(), mine.data(), mine.size());
  const std::vector<double> all = allgather(slot.data(), slot.size());
  std::string out;
  for (int r = 0; r < size_; ++r) {
    if (lengths[r] == 0) continue;
    const char* text = reinterpret_cast<const char*>(all.data() + r * slot.size());
    if (!out.empty()) out += "; ";
    out += "rank " + std::to_string(r) + ": " + std::string(text, static_cast<std::size_t>(lengths[r]));
  }
  return out;
}

void Communicator::check(bool ok, const std::string& message) const {
  std::string text = message;
  if (agree(ok ? 0 : -1, text) != 0) throw CollectiveError(text);
}

int Communicator::agree(int code, std::string& message) const {
  std::int64_t codes[2] = {code, -static_cast<std::int64_t>(code)};  // min, -max
  allreduce(codes, 2, ReduceOp::Min);
  const int most_severe = codes[0] < 0 ? static_cast<int>(codes[0]) : static_cast<int>(-codes[1]);
  if (most_severe == 0) return 0;
  std::string mine = code == 0 ? std::string() : message.empty() ? "code " + std::to_string(code) : message;
  message = gather_messages(mine);
  return most_severe;
}

void Communicator::abort(int code, const std::string& message) const noexcept {
  std::fprintf(stderr, "rank %d of %d: %s (aborting all ranks)\n", rank_, size_, message.c_str());
  std::fflush(stderr);
  if (mpi_) detail::mpi_abort(*mpi_, code);
  std::abort();
}

}  // namespace sphark
