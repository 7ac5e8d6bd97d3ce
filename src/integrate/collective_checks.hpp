#pragma once
// Option and argument checks of the steppers: in a distributed run every rank must throw
// together (before any collective that a throwing rank would skip), so the verdict is agreed
// over the ranks first. Private to src/integrate/.
#include <stdexcept>
#include <string>

#include "sphark/parallel/communicator.hpp"

namespace sphark::detail {

// Throws std::invalid_argument(message) if !ok; in a distributed run on every rank if !ok on
// any, with the failing ranks' messages ("rank r: ...").
inline void require_everywhere(const Communicator& comm, bool ok, const std::string& message) {
  if (!comm.distributed()) {
    if (!ok) throw std::invalid_argument(message);
    return;
  }
  std::string text = ok ? std::string() : message;
  if (comm.agree(ok ? 0 : -1, text) != 0) throw std::invalid_argument(text);
}

}  // namespace sphark::detail
