// Communicator: every collective gives the exact expected values on 1-4 ranks, and a failure on
// one rank reaches every rank with its message (check / agree / collectively).
#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>
#include <vector>

#include "mpi_env.hpp"
#include "sphark/parallel/mpi_session.hpp"

namespace sphark {
namespace {

using testing::world;

TEST(Communicator, BackedByMpiExactlyWhenBuiltWithIt) {
  EXPECT_EQ(world().distributed(), MpiSession::built_with_mpi());
  EXPECT_GE(world().rank(), 0);
  EXPECT_LT(world().rank(), world().size());
  const Communicator serial;
  EXPECT_FALSE(serial.distributed());
  EXPECT_EQ(serial.size(), 1);
  EXPECT_EQ(serial.allreduce(std::int64_t(7), ReduceOp::Sum), 7);
  EXPECT_EQ(serial.mpi_handle(), nullptr);
}

TEST(Communicator, ReductionsAreExact) {
  const Communicator& c = world();
  const std::int64_t p = c.size(), r = c.rank();
  EXPECT_EQ(c.allreduce(r, ReduceOp::Sum), p * (p - 1) / 2);
  EXPECT_EQ(c.allreduce(r, ReduceOp::Min), 0);
  EXPECT_EQ(c.allreduce(r, ReduceOp::Max), p - 1);
  double v[2] = {0.5 * double(r), -double(r)};
  c.allreduce(v, 2, ReduceOp::Max);
  EXPECT_EQ(v[0], 0.5 * double(p - 1));
  EXPECT_EQ(v[1], 0.0);
}

TEST(Communicator, AllgatherAndAlltoallPlaceEveryValue) {
  const Communicator& c = world();
  const std::int64_t mine[2] = {10 * c.rank(), 10 * c.rank() + 1};
  const std::vector<std::int64_t> all = c.allgather(mine, 2);
  ASSERT_EQ(all.size(), 2u * c.size());
  for (int r = 0; r < c.size(); ++r) EXPECT_EQ(all[2 * r + 1], 10 * r + 1);
  std::vector<std::int64_t> send(c.size());
  for (int r = 0; r < c.size(); ++r) send[r] = 100 * c.rank() + r;
  const std::vector<std::int64_t> got = c.alltoall(send);
  for (int r = 0; r < c.size(); ++r) EXPECT_EQ(got[r], 100 * r + c.rank());
}

// A ring (to rank + 1, from rank - 1) plus a message to itself, in one exchange.
TEST(Communicator, ExchangeDeliversRingAndSelfMessages) {
  const Communicator& c = world();
  const int next = (c.rank() + 1) % c.size(), prev = (c.rank() + c.size() - 1) % c.size();
  std::vector<double> to_next(5), to_self(3), from_prev(5, -1), from_self(3, -1);
  std::iota(to_next.begin(), to_next.end(), 1000.0 * c.rank());
  std::iota(to_self.begin(), to_self.end(), -7.0 * c.rank());
  std::vector<Communicator::Send> sends{{next, to_next.data(), 5 * sizeof(double)}};
  std::vector<Communicator::Receive> receives{{prev, from_prev.data(), 5 * sizeof(double)}};
  if (next != c.rank()) {  // one rank: the ring is the self message; keep one of each then
    sends.push_back({c.rank(), to_self.data(), 3 * sizeof(double)});
    receives.push_back({c.rank(), from_self.data(), 3 * sizeof(double)});
  }
  c.exchange(sends, receives);
  for (int k = 0; k < 5; ++k) EXPECT_EQ(from_prev[k], 1000.0 * prev + k);
  if (next != c.rank()) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(from_self[k], -7.0 * c.rank() + k);
  }
}

TEST(Communicator, CheckThrowsOnEveryRankWithTheFailingRanksMessages) {
  const Communicator& c = world();
  const int last = c.size() - 1;
  EXPECT_NO_THROW(c.check(true, "unused"));
  try {
    c.check(c.rank() != last, "disk full on " + std::to_string(c.rank()));
    ADD_FAILURE() << "no exception";
  } catch (const CollectiveError& e) {
    EXPECT_EQ(std::string(e.what()), "rank " + std::to_string(last) + ": disk full on " + std::to_string(last));
  }
}

TEST(Communicator, AgreeGivesTheMostSevereCode) {
  const Communicator& c = world();
  std::string message = "ok";
  EXPECT_EQ(c.agree(0, message), 0);
  EXPECT_EQ(message, "ok");  // untouched when every rank is fine
  message = "recoverable " + std::to_string(c.rank());
  EXPECT_EQ(c.agree(1 + c.rank(), message), c.size());  // all positive: the largest
  EXPECT_NE(message.find("rank 0: recoverable 0"), std::string::npos);
  const int last = c.size() - 1;
  message = c.rank() == last ? "fatal" : "slow";
  const int code = c.rank() == last ? -3 : (c.rank() == 0 ? 2 : 0);
  EXPECT_EQ(c.agree(code, message), -3);
  EXPECT_NE(message.find("rank " + std::to_string(last) + ": fatal"), std::string::npos);
}

TEST(Communicator, CollectivelyTurnsOneRanksExceptionIntoEveryRanks) {
  const Communicator& c = world();
  const int last = c.size() - 1;
  EXPECT_THROW(c.collectively([&] {
    if (c.rank() == last) throw std::runtime_error("bad input");
  }),
               CollectiveError);
  std::string messages = c.gather_messages(c.rank() % 2 == 1 ? "odd" : "");
  for (int r = 1; r < c.size(); r += 2) EXPECT_NE(messages.find("rank " + std::to_string(r) + ": odd"), std::string::npos);
  EXPECT_EQ(messages.find("rank 0"), std::string::npos);
}

}  // namespace
}  // namespace sphark
