#include "sphark/run/guarded_system.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace sphark {

std::string describe_entries(const StateLayout& layout, const std::vector<std::size_t>& entries,
                             std::size_t max_named) {
  if (entries.empty()) return {};
  std::string out;
  for (Field f : layout.fields()) {
    const std::size_t off = layout.offset(f), end = off + layout.field_size(f);
    std::vector<std::size_t> particles;
    for (std::size_t k : entries)
      if (k >= off && k < end) {
        const std::size_t p = (k - off) / static_cast<std::size_t>(layout.components(f));
        if (particles.empty() || particles.back() != p) particles.push_back(p);
      }
    if (particles.empty()) continue;
    if (!out.empty()) out += "; ";
    out += std::string(field_name(f)) + " of particle" + (particles.size() > 1 ? "s " : " ");
    for (std::size_t i = 0; i < particles.size() && i < max_named; ++i) {
      if (i) out += ", ";
      out += std::to_string(particles[i]);
    }
    if (particles.size() > max_named) out += " (+" + std::to_string(particles.size() - max_named) + " more)";
  }
  return out;
}

std::vector<std::size_t> nonphysical_entries(const StateLayout& layout, const Real* y) {
  std::vector<std::size_t> bad;
  const auto range = [&](Field f) {  // [begin, end) of a field's entries, empty if absent
    const std::size_t b = layout.has(f) ? layout.offset(f) : 0;
    return std::pair{b, layout.has(f) ? b + layout.field_size(f) : b};
  };
  const auto [r0, r1] = range(Field::Density);         // rho > 0
  const auto [u0, u1] = range(Field::InternalEnergy);  // u >= 0
  for (std::size_t k = 0; k < layout.size(); ++k)
    if (!std::isfinite(y[k]) || (k >= r0 && k < r1 && !(y[k] > 0)) || (k >= u0 && k < u1 && y[k] < 0)) bad.push_back(k);
  return bad;
}

int GuardedSystem::check(Real t, const Real* out, std::size_t n, const char* what) {
  std::vector<std::size_t> bad;
  for (std::size_t k = 0; k < n; ++k)
    if (!std::isfinite(out[k])) bad.push_back(k);
  if (bad.empty()) return 0;
  char at[64];
  std::snprintf(at, sizeof at, " at t=%.9g", t);
  own_error_ = true;
  error_ = std::string("non-finite ") + what + at + ": " + describe_entries(layout_, bad);
  ++failures_;
  return 1;
}

int GuardedSystem::rhs(Real t, const Real* y, Real* ydot) {
  own_error_ = false;
  // A non-finite or non-physical state: the inner system normally returns > 0 itself; make
  // sure (and name up to a few particles).
  if (const std::vector<std::size_t> bad = nonphysical_entries(layout_, y); !bad.empty()) {
    char at[64];
    std::snprintf(at, sizeof at, " at t=%.9g", t);
    own_error_ = true;
    error_ = std::string("non-finite or non-physical state") + at + ": " + describe_entries(layout_, bad);
    ++failures_;
    return 1;
  }
  const int r = inner_.rhs(t, y, ydot);
  if (r != 0) return r;
  if (t >= inject_from_)  // particle 0's velocity derivative (or the first state entry)
    ydot[layout_.has(Field::Velocity) ? layout_.offset(Field::Velocity) : 0] = std::numeric_limits<Real>::quiet_NaN();
  return check(t, ydot, size(), "time derivative");
}

int GuardedSystem::stiff_diagonal(Real t, const Real* y, Real* c) {
  own_error_ = false;
  const int r = inner_.stiff_diagonal(t, y, c);
  if (r != 0) return r;
  return check(t, c, size(), "stiff diagonal");
}

}  // namespace sphark
