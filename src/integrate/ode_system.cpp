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

std::vector<std::size_t> OdeSystem::entry_particles() const {
  std::vector<std::size_t> owner(size(), 0);
  const StateLayout* layout = state_layout();
  if (layout == nullptr) return owner;
  std::size_t first = 0;  // global index of the species' first particle
  for (const auto& block : layout->species()) {
    for (const auto& f : block.fields) {
      const auto c = static_cast<std::size_t>(f.components);
      for (std::size_t p = 0; p < block.count; ++p)
        for (std::size_t k = 0; k < c; ++k) owner[f.offset + p * c + k] = first + p;
    }
    first += block.count;
  }
  return owner;
}

}  // namespace sphark
