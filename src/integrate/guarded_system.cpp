#include "sphark/integrate/guarded_system.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace sphark {

namespace {
// The particles (ascending, unique) of `entries` inside one field's block.
std::vector<std::size_t> particles_in(const StateLayout::FieldSlot& f, std::size_t count,
                                      const std::vector<std::size_t>& entries) {
  const std::size_t end = f.offset + count * static_cast<std::size_t>(f.components);
  std::vector<std::size_t> particles;
  for (std::size_t k : entries)
    if (k >= f.offset && k < end) {
      const std::size_t p = (k - f.offset) / static_cast<std::size_t>(f.components);
      if (particles.empty() || particles.back() != p) particles.push_back(p);
    }
  return particles;
}

// The entries k of [begin, end) with bad(y[k]), ascending. A counting pass first, in parallel and
// without a branch per entry (the common case: none); the list only when there are some.
template <class Bad>
void append_where(const Real* y, std::size_t begin, std::size_t end, Bad bad, std::vector<std::size_t>& out) {
  std::size_t count = 0;
#pragma omp parallel for simd schedule(static) reduction(+ : count) if (end - begin > 32768)
  for (std::size_t k = begin; k < end; ++k) count += bad(y[k]) ? 1 : 0;
  if (count == 0) return;
  for (std::size_t k = begin; k < end; ++k)
    if (bad(y[k])) out.push_back(k);
}

// Not finite: NaN or +-inf (|v| <= max is false for both), a comparison the compiler vectorises.
struct NotFinite {
  bool operator()(Real v) const { return !(std::abs(v) <= std::numeric_limits<Real>::max()); }
};
constexpr NotFinite not_finite;
}  // namespace

std::string describe_entries(const StateLayout& layout, const std::vector<std::size_t>& entries,
                             std::size_t max_named) {
  std::string out;
  for (std::size_t s = 0; s < layout.species().size(); ++s) {
    const auto& block = layout.species()[s];
    for (const auto& f : block.fields) {
      const std::vector<std::size_t> particles = particles_in(f, block.count, entries);
      if (particles.empty()) continue;
      if (!out.empty()) out += "; ";
      if (s > 0) out += std::string(block.species.name()) + " ";
      out += std::string(f.field.name()) + " of particle" + (particles.size() > 1 ? "s " : " ");
      for (std::size_t i = 0; i < particles.size() && i < max_named; ++i) {
        if (i) out += ", ";
        out += std::to_string(particles[i]);
      }
      if (particles.size() > max_named) out += " (+" + std::to_string(particles.size() - max_named) + " more)";
    }
  }
  return out;
}

std::vector<std::size_t> nonphysical_entries(const StateLayout& layout, const Real* y) {
  std::vector<std::size_t> bad;
  for (const auto& block : layout.species())
    for (const auto& f : block.fields) {
      const std::size_t end = f.offset + block.count * static_cast<std::size_t>(f.components);
      if (f.field == Field::Density) append_where(y, f.offset, end, [](Real v) { return !(v > 0) || not_finite(v); }, bad);
      else if (f.field == Field::InternalEnergy) append_where(y, f.offset, end, [](Real v) { return !(v >= 0) || not_finite(v); }, bad);
      else append_where(y, f.offset, end, not_finite, bad);
    }
  return bad;
}

int GuardedSystem::fail(Real t, const std::string& what, const std::vector<std::size_t>& entries) {
  char at[64];
  std::snprintf(at, sizeof at, " at t=%.9g: ", t);
  own_error_ = true;
  const StateLayout* layout = inner_.state_layout();
  std::string where;
  if (layout) {
    where = describe_entries(*layout, entries);
  } else {
    where = "entr" + std::string(entries.size() > 1 ? "ies " : "y ") + std::to_string(entries.front());
    if (entries.size() > 1) where += " (+" + std::to_string(entries.size() - 1) + " more)";
  }
  error_ = what + at + where;
  ++failures_;
  return 1;
}

int GuardedSystem::check(Real t, const Real* out, std::size_t n, const char* what) {
  std::vector<std::size_t> bad;
  append_where(out, 0, n, not_finite, bad);
  return bad.empty() ? 0 : fail(t, std::string("non-finite ") + what, bad);
}

int GuardedSystem::check_state(Real t, const Real* y) {
  own_error_ = false;
  const StateLayout* layout = inner_.state_layout();
  if (layout) {
    if (const std::vector<std::size_t> bad = nonphysical_entries(*layout, y); !bad.empty())
      return fail(t, "non-finite or non-physical state", bad);
    return 0;
  }
  return check(t, y, size(), "state");
}

int GuardedSystem::check_derivative(Real t, Real* ydot) {
  const StateLayout* layout = inner_.state_layout();
  if (t >= inject_from_)  // particle 0's velocity derivative (or the first state entry)
    ydot[layout && layout->has(Field::Velocity) ? layout->offset(Field::Velocity) : 0] =
        std::numeric_limits<Real>::quiet_NaN();
  return check(t, ydot, size(), "time derivative");
}

int GuardedSystem::rhs(Real t, const Real* y, Real* ydot) {
  if (const int r = check_state(t, y)) return r;
  particle_evals_ += static_cast<long>(inner_.num_particles());  // issue #17: the unit of work
  const int r = inner_.rhs(t, y, ydot);
  return r != 0 ? r : check_derivative(t, ydot);
}

int GuardedSystem::rhs_subset(Real t, const Real* y, std::span<const std::size_t> active, Real* ydot) {
  if (const int r = check_state(t, y)) return r;
  particle_evals_ += static_cast<long>(active.size());
  const int r = inner_.rhs_subset(t, y, active, ydot);
  return r != 0 ? r : check_derivative(t, ydot);
}

int GuardedSystem::stiff_diagonal(Real t, const Real* y, Real* c) {
  own_error_ = false;
  const int r = inner_.stiff_diagonal(t, y, c);
  if (r != 0) return r;
  return check(t, c, size(), "stiff diagonal");
}

}  // namespace sphark
