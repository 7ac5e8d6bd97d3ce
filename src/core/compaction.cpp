#include "sphark/core/compaction.hpp"

#include <algorithm>
#include <stdexcept>

namespace sphark {

void check_removal_list(const std::vector<std::uint32_t>& removed, std::size_t n) {
  for (std::size_t k = 0; k < removed.size(); ++k) {
    if (removed[k] >= n) throw std::invalid_argument("compaction: removed index out of range");
    if (k > 0 && removed[k] <= removed[k - 1])
      throw std::invalid_argument("compaction: removed indices must be strictly ascending");
  }
}

namespace {
template <class T>
std::size_t compact_impl(T* data, std::size_t n, std::size_t c, const std::vector<std::uint32_t>& removed) {
  check_removal_list(removed, n);
  std::size_t write = removed.empty() ? n : removed[0];  // items before the first removal stay put
  std::size_t next = 0;
  for (std::size_t read = write; read < n; ++read) {
    if (next < removed.size() && removed[next] == read) {
      ++next;
      continue;
    }
    std::copy(data + c * read, data + c * (read + 1), data + c * write);
    ++write;
  }
  return write;
}

template <class T>
void compact_vector(std::vector<T>& field, std::size_t c, const std::vector<std::uint32_t>& removed) {
  if (c == 0 || field.size() % c != 0) throw std::invalid_argument("compact: field size is not a multiple of components");
  const std::size_t left = compact_impl(field.data(), field.size() / c, c, removed);
  field.resize(c * left);
}
}  // namespace

std::size_t compact_field(Real* data, std::size_t n, std::size_t components, const std::vector<std::uint32_t>& removed) {
  return compact_impl(data, n, components, removed);
}
std::size_t compact_field(std::uint32_t* data, std::size_t n, std::size_t components,
                          const std::vector<std::uint32_t>& removed) {
  return compact_impl(data, n, components, removed);
}
void compact(std::vector<Real>& field, std::size_t components, const std::vector<std::uint32_t>& removed) {
  compact_vector(field, components, removed);
}
void compact(std::vector<std::uint32_t>& field, std::size_t components, const std::vector<std::uint32_t>& removed) {
  compact_vector(field, components, removed);
}

std::vector<std::uint32_t> surviving_indices(std::size_t n, const std::vector<std::uint32_t>& removed) {
  check_removal_list(removed, n);
  std::vector<std::uint32_t> kept;
  kept.reserve(n - removed.size());
  std::size_t next = 0;
  for (std::size_t a = 0; a < n; ++a) {
    if (next < removed.size() && removed[next] == a) {
      ++next;
      continue;
    }
    kept.push_back(static_cast<std::uint32_t>(a));
  }
  return kept;
}

}  // namespace sphark
