#include "sphark/core/profile.hpp"

#include <cstdio>
#include <ostream>

namespace sphark {

const char* phase_name(Phase p) {
  switch (p) {
    case Phase::Neighbours: return "neighbours";
    case Phase::DensityH: return "density/h solve";
    case Phase::Forces: return "forces";
    case Phase::Rhs: return "rhs (total)";
    case Phase::Advance: return "advance (total)";
    case Phase::Output: return "output";
    case Phase::Halo: return "halo exchange (+ waiting)";
    case Phase::Count: break;
  }
  return "?";
}

RunProfile& run_profile() {
  static RunProfile profile;
  return profile;
}

void RunProfile::print(std::ostream& os, double wall) const {
  auto line = [&](const char* name, double s, long calls) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "  %-34s %10.3f s %6.1f %%  %9ld calls\n", name, s,
                  wall > 0 ? 100.0 * s / wall : 0.0, calls);
    os << buf;
  };
  const double rhs = seconds(Phase::Rhs);
  const double advance = seconds(Phase::Advance);
  const double parts = seconds(Phase::Neighbours) + seconds(Phase::DensityH) + seconds(Phase::Forces) +
                       seconds(Phase::Halo);
  os << "profile (wall time):\n";
  line("neighbours", seconds(Phase::Neighbours), calls(Phase::Neighbours));
  line("density/h solve", seconds(Phase::DensityH), calls(Phase::DensityH));
  line("forces", seconds(Phase::Forces), calls(Phase::Forces));
  if (calls(Phase::Halo) > 0) line("halo exchange (+ waiting)", seconds(Phase::Halo), calls(Phase::Halo));
  line("other rhs work", rhs > parts ? rhs - parts : 0.0, calls(Phase::Rhs));
  line("stepper (ARKODE vector work etc.)", advance > rhs ? advance - rhs : 0.0,
       calls(Phase::Advance));
  line("output", seconds(Phase::Output), calls(Phase::Output));
  const double accounted = (advance > rhs ? advance : rhs) + seconds(Phase::Output);
  line("set-up and rest", wall > accounted ? wall - accounted : 0.0, 0);
  line("total", wall, 0);
  if (tallied(Tally::ListBuilds) > 0 || tallied(Tally::DensitySolves) > 0)
    os << "  work: " << tallied(Tally::ListBuilds) << " neighbour list builds, " << tallied(Tally::DensitySolves)
       << " density/h solves (particles)\n";
}

}  // namespace sphark
