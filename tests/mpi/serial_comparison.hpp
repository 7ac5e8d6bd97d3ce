#pragma once
// A distributed run against the serial run of the same particles (the scheme tests of
// tests/mpi/): every field of every particle, matched by global id, must be equal bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "mpi_env.hpp"
#include "sphark/core/types.hpp"
#include "sphark/integrate/stepper.hpp"

namespace sphark::testing {

// Per particle by global id: the values compared.
using FieldsById = std::map<std::int64_t, std::vector<Real>>;

struct RunOutcome {
  FieldsById fields;       // this rank's particles (the serial run: all)
  long steps = 0;
  std::size_t migrated = 0;  // particles sent by this rank
  std::size_t moved = 0;     // of those, at the migrations without a repartition (crossed by motion)
};

// The stepper of both runs: `method` with fixed steps of dt, or adaptive (dt = 0) with rtol =
// atol = tol and reproducible norms (the same steps on any number of ranks).
inline StepperOptions comparison_options(const std::string& method, Real dt, Real tol, const Communicator& comm) {
  StepperOptions o;
  o.method = method;
  if (dt > 0) o.fixed_dt = dt;
  o.rtol = tol;
  o.atol = {tol};
  o.reproducible_norms = !(dt > 0);
  o.communicator = comm;
  return o;
}

// Collective. Every particle once, every value equal, the same steps (and `fixed_steps` of them
// if > 0); on more than one rank (if `moving`), particles crossed the domains by motion. Rank 0
// prints a line.
inline void expect_equal_to_serial(const std::string& name, const RunOutcome& serial, const RunOutcome& dist,
                                   long fixed_steps, bool moving = true) {
  Real worst = 0;
  std::int64_t missing = 0, unequal = 0;
  for (const auto& [id, f] : dist.fields) {
    const auto it = serial.fields.find(id);
    if (it == serial.fields.end() || it->second.size() != f.size()) {
      ++missing;
      continue;
    }
    for (std::size_t k = 0; k < f.size(); ++k) {
      unequal += f[k] != it->second[k];
      worst = std::max(worst, std::abs(f[k] - it->second[k]) / std::max(1.0, std::abs(it->second[k])));
    }
  }
  worst = global_max(worst);
  const std::int64_t migrated = global_sum(static_cast<std::int64_t>(dist.migrated));
  const std::int64_t moved = global_sum(static_cast<std::int64_t>(dist.moved));
  EXPECT_EQ(global_sum(missing), 0) << name;
  EXPECT_EQ(global_sum(static_cast<std::int64_t>(dist.fields.size())), static_cast<std::int64_t>(serial.fields.size()));
  EXPECT_EQ(global_sum(unequal), 0) << name << ": max relative difference " << worst;
  EXPECT_EQ(dist.steps, serial.steps) << name;
  if (fixed_steps > 0) {
    EXPECT_EQ(serial.steps, fixed_steps);
  }
  if (world().size() > 1 && moving) {
    EXPECT_GT(moved, 0);  // particles crossed the domains' boundaries
    EXPECT_GT(migrated, moved);
  }
  if (world().rank() == 0)
    std::printf("%s on %d ranks: %zu particles, %zu fields each, %ld steps, max relative difference to serial %.3g, "
                "%lld particles migrated (%lld of them by motion, outside the repartition)\n",
                name.c_str(), world().size(), serial.fields.size(), serial.fields.begin()->second.size(), dist.steps,
                worst, static_cast<long long>(migrated), static_cast<long long>(moved));
}

}  // namespace sphark::testing
