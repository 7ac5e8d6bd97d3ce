#include "sphark/parallel/global_state.hpp"

#include <numeric>
#include <stdexcept>
#include <string>

#include "sphark/parallel/migration.hpp"

namespace sphark {

std::vector<int> field_components(const StateLayout& layout) {
  std::vector<int> c;
  for (const Field f : layout.fields()) c.push_back(layout.components(f));
  return c;
}

namespace {
std::size_t per_particle(const std::vector<int>& components) {
  return static_cast<std::size_t>(std::accumulate(components.begin(), components.end(), 0));
}
}  // namespace

std::vector<Real> select_particles(const std::vector<Real>& all, const std::vector<int>& components, std::size_t count,
                                   const std::vector<std::int64_t>& ids) {
  if (all.size() != count * per_particle(components))
    throw std::invalid_argument("select_particles: " + std::to_string(all.size()) + " values do not fit " +
                                std::to_string(count) + " particles");
  std::vector<Real> out;
  out.reserve(ids.size() * per_particle(components));
  std::size_t offset = 0;
  for (const int comps : components) {
    const std::size_t c = static_cast<std::size_t>(comps);
    for (const std::int64_t id : ids) {
      if (id < 0 || static_cast<std::size_t>(id) >= count)
        throw std::invalid_argument("select_particles: id " + std::to_string(id) + " outside [0, " +
                                    std::to_string(count) + ")");
      for (std::size_t k = 0; k < c; ++k) out.push_back(all[offset + c * static_cast<std::size_t>(id) + k]);
    }
    offset += c * count;
  }
  return out;
}

std::vector<Real> gather_particles(const Communicator& comm, const std::vector<std::int64_t>& ids,
                                   const std::vector<Real>& local, const std::vector<int>& components) {
  std::vector<std::int64_t> moved_ids = ids;
  std::vector<Real> moved = local;
  ParticleData data;
  data.ids = &moved_ids;
  data.states = {{&moved, components}};
  migrate(comm, std::vector<int>(ids.size(), 0), data);  // every particle to rank 0
  if (comm.rank() != 0) return {};
  const std::size_t n = moved_ids.size();
  std::vector<char> seen(n, 0);
  for (const std::int64_t id : moved_ids) {
    if (id < 0 || static_cast<std::size_t>(id) >= n || seen[static_cast<std::size_t>(id)])
      throw std::runtime_error("gather_particles: the global ids are not 0 .. " + std::to_string(n) + " - 1 each once");
    seen[static_cast<std::size_t>(id)] = 1;
  }
  std::vector<Real> out(moved.size());
  std::size_t offset = 0;
  for (const int comps : components) {
    const std::size_t c = static_cast<std::size_t>(comps);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < c; ++k) out[offset + c * static_cast<std::size_t>(moved_ids[i]) + k] = moved[offset + c * i + k];
    offset += c * n;
  }
  return out;
}

}  // namespace sphark
