#include "sphark/parallel/global_state.hpp"

#include <stdexcept>
#include <string>

#include "sphark/parallel/migration.hpp"

namespace sphark {

std::vector<int> field_components(const StateLayout& layout) {
  std::vector<int> c;
  for (const Field f : layout.fields()) c.push_back(layout.components(f));
  return c;
}

std::vector<Real> share_of(const StateLayout& whole, const std::vector<Real>& all, const std::vector<std::int64_t>& ids) {
  if (all.size() != whole.size())
    throw std::invalid_argument("share_of: " + std::to_string(all.size()) + " values do not fit a state of " +
                                std::to_string(whole.size()));
  std::vector<std::size_t> keep(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] < 0) throw std::invalid_argument("share_of: negative id " + std::to_string(ids[i]));
    keep[i] = static_cast<std::size_t>(ids[i]);
  }
  return resize_species(whole, all.data(), whole.with_count(whole.primary(), keep.size()), whole.primary(), keep);
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
