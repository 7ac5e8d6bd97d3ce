#pragma once
// The world of the MPI test program (tests/mpi/main.cpp) and the collective assertion helpers:
// a test must never let one rank leave a collective sequence early (an ASSERT on one rank
// would make the others wait forever), so local verdicts are reduced first and asserted on
// every rank.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "sphark/parallel/communicator.hpp"

namespace sphark::testing {

const Communicator& world();

// Number of ranks on which `failed` is true (collective).
inline std::int64_t ranks_failing(bool failed) {
  return world().allreduce(std::int64_t(failed ? 1 : 0), ReduceOp::Sum);
}

// Sum over the ranks (collective).
inline std::int64_t global_sum(std::int64_t v) { return world().allreduce(v, ReduceOp::Sum); }
inline double global_max(double v) { return world().allreduce(v, ReduceOp::Max); }

}  // namespace sphark::testing
