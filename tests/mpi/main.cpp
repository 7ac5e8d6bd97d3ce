// main() of test_mpi: one MPI session for all tests; ranks > 0 print only their failures (with
// the rank), rank 0 prints the usual GoogleTest report.
#include <gtest/gtest.h>

#include <cstdio>

#include "mpi_env.hpp"
#include "sphark/parallel/mpi_session.hpp"

namespace sphark::testing {
namespace {

const MpiSession* g_session = nullptr;

class FailuresOnly : public ::testing::EmptyTestEventListener {
 public:
  explicit FailuresOnly(int rank) : rank_(rank) {}
  void OnTestPartResult(const ::testing::TestPartResult& r) override {
    if (!r.failed()) return;
    std::fprintf(stderr, "[rank %d] %s:%d: failure\n%s\n", rank_, r.file_name() ? r.file_name() : "?", r.line_number(),
                 r.summary());
  }

 private:
  int rank_;
};

}  // namespace

const Communicator& world() { return g_session->world(); }

}  // namespace sphark::testing

int main(int argc, char** argv) {
  sphark::MpiSession session(argc, argv);
  sphark::testing::g_session = &session;
  ::testing::InitGoogleTest(&argc, argv);
  const int rank = session.world().rank();
  if (rank != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
    listeners.Append(new sphark::testing::FailuresOnly(rank));
  }
  return session.run([](const sphark::Communicator&) { return RUN_ALL_TESTS(); });
}
