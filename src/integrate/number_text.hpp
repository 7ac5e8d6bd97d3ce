#pragma once
// Numbers in the steppers' messages: a time to every digit (so that a message names the exact
// time of a failure or an event), and any other number as the stream prints it.
#include <cstdio>
#include <sstream>
#include <string>

#include "sphark/core/types.hpp"

namespace sphark::detail {

inline std::string at_time(Real t) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", t);
  return buf;
}

inline std::string number_text(Real x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

}  // namespace sphark::detail
