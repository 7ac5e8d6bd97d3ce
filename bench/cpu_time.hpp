#pragma once
// CPU time of this process (all threads), for the end-to-end timing drivers in bench/.
#include <sys/resource.h>

namespace sphark::bench {
inline double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}
}  // namespace sphark::bench
