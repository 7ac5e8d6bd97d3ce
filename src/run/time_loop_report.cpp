// The end of a time loop told to the user, and the diagnostics text read back (see
// sphark/run/time_loop.hpp).
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "sphark/run/time_loop.hpp"

namespace sphark {

int report_time_loop_end(const TimeLoopResult& r, bool print) {
  const char* p = r.program.c_str();
  if (!print) return r.ok() ? 0 : r.status == TimeLoopStatus::Stopped ? 128 + r.signal : 3;
  switch (r.status) {
    case TimeLoopStatus::Reached:
    case TimeLoopStatus::EndedEarly: return 0;
    case TimeLoopStatus::Stopped:
      if (r.checkpoint.empty()) {  // a distributed run (no checkpoints yet)
        std::fprintf(stderr, "%s: %s run stopped by signal %d at t=%.9g; no checkpoint\n", p, r.run.c_str(), r.signal,
                     r.t_reached);
        return 128 + r.signal;
      }
      std::fprintf(stderr, "%s: %s run stopped by signal %d at t=%.9g; checkpoint %s (continue with --restart %s)\n", p,
                   r.run.c_str(), r.signal, r.t_reached, r.checkpoint.c_str(), r.checkpoint.c_str());
      return 128 + r.signal;
    case TimeLoopStatus::Failed:
      std::fprintf(stderr, "%s: %s run FAILED at t=%.9g: %s\n%s: last good state: %s%s%s\n", p, r.run.c_str(),
                   r.t_reached, r.failure.c_str(), p, r.last_frame.empty() ? "" : r.last_frame.c_str(),
                   r.last_frame.empty() ? "" : " and ", r.checkpoint.c_str());
      return 3;
  }
  return 1;
}

std::vector<Real> csv_column(const std::string& text, const std::string& column) {
  std::istringstream in(text);
  std::string line, cell;
  std::getline(in, line);
  std::istringstream head(line);
  int index = -1;
  for (int i = 0; std::getline(head, cell, ','); ++i)
    if (cell == column) index = i;
  if (index < 0) throw std::runtime_error("no column '" + column + "' in the diagnostics");
  std::vector<Real> out;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    for (int i = 0; std::getline(row, cell, ','); ++i)
      if (i == index) out.push_back(std::stod(cell));
  }
  return out;
}

}  // namespace sphark
