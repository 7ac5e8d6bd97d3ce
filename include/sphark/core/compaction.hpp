#pragma once
// Removing particles from structure-of-arrays fields (e.g. gas accreted by a sink): every field
// holds n items of `components` consecutive values; the listed items are dropped and the others
// move down in their order, each value copied unchanged (bit for bit).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark {

// Throws std::invalid_argument unless `removed` is strictly ascending with every entry < n.
void check_removal_list(const std::vector<std::uint32_t>& removed, std::size_t n);

// In place over data[0 .. components n); returns the new item count n - removed.size().
std::size_t compact_field(Real* data, std::size_t n, std::size_t components, const std::vector<std::uint32_t>& removed);
std::size_t compact_field(std::uint32_t* data, std::size_t n, std::size_t components,
                          const std::vector<std::uint32_t>& removed);

// The vector's size must be components n; it is resized to components (n - removed.size()).
void compact(std::vector<Real>& field, std::size_t components, const std::vector<std::uint32_t>& removed);
void compact(std::vector<std::uint32_t>& field, std::size_t components, const std::vector<std::uint32_t>& removed);

// The survivors' old indices, in order (new index i held old index kept[i]).
std::vector<std::uint32_t> surviving_indices(std::size_t n, const std::vector<std::uint32_t>& removed);

}  // namespace sphark
