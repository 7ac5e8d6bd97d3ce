#include "sphark/state/state_layout.hpp"

#include <algorithm>

namespace sphark {

namespace state_detail {
void wrong_components(Field f, int expected, int actual) {
  throw std::logic_error("state field " + std::string(f.name()) + ": expected " + std::to_string(expected) +
                         " components, the layout has " + std::to_string(actual));
}
}  // namespace state_detail

namespace {
std::string quoted(std::string_view s) { return "'" + std::string(s) + "'"; }
}  // namespace

StateLayout& StateLayout::add_species(Species s, std::size_t count) {
  if (has(s)) throw std::invalid_argument("StateLayout::add_species: species added twice: " + quoted(s.name()));
  blocks_.push_back({s, count, size_, {}});
  return *this;
}

StateLayout& StateLayout::add(Field f, int components) {
  if (blocks_.empty()) throw std::logic_error("StateLayout::add: no species to add field " + quoted(f.name()) + " to");
  return add(blocks_.back().species, f, components);
}

StateLayout& StateLayout::add(Species s, Field f, int components) {
  if (components <= 0) throw std::invalid_argument("StateLayout::add: components must be positive");
  if (has(s, f))
    throw std::invalid_argument("StateLayout::add: field added twice: " + quoted(f.name()) + " of " + quoted(s.name()));
  block(s).fields.push_back({f, components, 0});
  relayout();
  return *this;
}

void StateLayout::relayout() {
  std::size_t o = 0;
  for (SpeciesBlock& b : blocks_) {
    b.offset = o;
    for (FieldSlot& f : b.fields) {
      f.offset = o;
      o += b.count * static_cast<std::size_t>(f.components);
    }
  }
  size_ = o;
}

const StateLayout::SpeciesBlock* StateLayout::find(Species s) const {
  for (const SpeciesBlock& b : blocks_)
    if (b.species == s) return &b;
  return nullptr;
}

StateLayout::SpeciesBlock& StateLayout::block(Species s) {
  for (SpeciesBlock& b : blocks_)
    if (b.species == s) return b;
  throw std::out_of_range("StateLayout: no species " + quoted(s.name()) + " in this state");
}

Species StateLayout::primary() const {
  if (blocks_.empty()) throw std::out_of_range("StateLayout: empty layout");
  return blocks_.front().species;
}

bool StateLayout::has(Species s, Field f) const {
  const SpeciesBlock* b = find(s);
  if (!b) return false;
  return std::any_of(b->fields.begin(), b->fields.end(), [&](const FieldSlot& x) { return x.field == f; });
}

const StateLayout::FieldSlot& StateLayout::slot(Species s, Field f) const {
  const SpeciesBlock* b = find(s);
  if (!b) throw std::out_of_range("StateLayout: no species " + quoted(s.name()) + " in this state");
  for (const FieldSlot& x : b->fields)
    if (x.field == f) return x;
  throw std::out_of_range("StateLayout: field not in this state: " + std::string(f.name()) +
                          (blocks_.size() > 1 ? " of " + quoted(s.name()) : std::string()));
}

std::size_t StateLayout::field_size(Species s, Field f) const {
  return has(s, f) ? particles(s) * static_cast<std::size_t>(slot(s, f).components) : 0;
}

std::size_t StateLayout::particles(Species s) const {
  const SpeciesBlock* b = find(s);
  return b ? b->count : 0;
}

std::vector<Field> StateLayout::fields() const { return blocks_.empty() ? std::vector<Field>{} : fields(primary()); }

std::vector<Field> StateLayout::fields(Species s) const {
  std::vector<Field> out;
  if (const SpeciesBlock* b = find(s))
    for (const FieldSlot& x : b->fields) out.push_back(x.field);
  return out;
}

StateLayout StateLayout::with_count(Species s, std::size_t count) const {
  StateLayout L = *this;
  L.block(s).count = count;
  L.relayout();
  return L;
}

bool StateLayout::operator==(const StateLayout& o) const {
  if (blocks_.size() != o.blocks_.size() || size_ != o.size_) return false;
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    const SpeciesBlock &a = blocks_[i], &b = o.blocks_[i];
    if (!(a.species == b.species) || a.count != b.count || a.fields.size() != b.fields.size()) return false;
    for (std::size_t k = 0; k < a.fields.size(); ++k)
      if (!(a.fields[k].field == b.fields[k].field) || a.fields[k].components != b.fields[k].components) return false;
  }
  return true;
}

std::vector<Real> resize_species(const StateLayout& from, const Real* y_from, const StateLayout& to, Species s,
                                 const std::vector<std::size_t>& keep) {
  if (!(from.with_count(s, to.particles(s)) == to))
    throw std::invalid_argument("resize_species: the layouts differ in more than the count of " +
                                quoted(s.name()));
  const std::size_t old_count = from.particles(s), new_count = to.particles(s);
  if (keep.size() > new_count)
    throw std::invalid_argument("resize_species: " + std::to_string(keep.size()) + " kept particles, room for " +
                                std::to_string(new_count));
  for (std::size_t i : keep)
    if (i >= old_count)
      throw std::invalid_argument("resize_species: particle " + std::to_string(i) + " out of range (" +
                                  std::to_string(old_count) + " particles)");
  std::vector<Real> y(to.size(), 0.0);
  for (std::size_t b = 0; b < to.species().size(); ++b) {
    const auto& old_block = from.species()[b];
    const auto& new_block = to.species()[b];
    for (std::size_t k = 0; k < new_block.fields.size(); ++k) {
      const std::size_t c = static_cast<std::size_t>(new_block.fields[k].components);
      const Real* src = y_from + old_block.fields[k].offset;
      Real* dst = y.data() + new_block.fields[k].offset;
      if (!(new_block.species == s)) {
        std::copy(src, src + c * new_block.count, dst);
        continue;
      }
      for (std::size_t i = 0; i < keep.size(); ++i) std::copy(src + c * keep[i], src + c * (keep[i] + 1), dst + c * i);
    }
  }
  return y;
}

// resize_species applied to the entries' numbers (1-based: the zeros it leaves have no source).
std::vector<std::size_t> entry_sources(const StateLayout& from, const StateLayout& to, Species s,
                                       const std::vector<std::size_t>& keep) {
  std::vector<Real> number(from.size());
  for (std::size_t k = 0; k < number.size(); ++k) number[k] = static_cast<Real>(k + 1);
  const std::vector<Real> moved = resize_species(from, number.data(), to, s, keep);
  std::vector<std::size_t> source(moved.size());
  for (std::size_t k = 0; k < moved.size(); ++k)
    source[k] = moved[k] == 0 ? kNoEntrySource : static_cast<std::size_t>(moved[k]) - 1;
  return source;
}

std::vector<Real> per_field_tolerance(const StateLayout& L, const std::vector<std::pair<Field, Real>>& atol,
                                      Real fallback) {
  std::vector<Real> out(L.size(), fallback);
  for (const auto& [f, value] : atol) {
    if (!L.has(f)) continue;
    const std::size_t o = L.offset(f);
    for (std::size_t i = 0; i < L.field_size(f); ++i) out[o + i] = value;
  }
  return out;
}

}  // namespace sphark
