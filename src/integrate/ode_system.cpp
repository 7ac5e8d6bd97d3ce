// The defaults of OdeSystem that need a StateLayout (integrate/ode_system.hpp).
#include "sphark/integrate/ode_system.hpp"

#include "sphark/state/state_layout.hpp"

namespace sphark {

// Every particle of every species; a plain ODE (no layout) counts as one particle.
std::size_t OdeSystem::num_particles() const {
  const StateLayout* layout = state_layout();
  if (layout == nullptr) return 1;
  std::size_t n = 0;
  for (const auto& block : layout->species()) n += block.count;
  return n;
}

}  // namespace sphark
