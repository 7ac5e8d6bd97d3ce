// Particles removed inside a top step (StepperOptions::remove_active; the scheme is described in
// block_leapfrog_stepper.cpp): the system's new state, and every per-entry and per-particle
// array of the stepper following the entries' sources.
#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>

#include "block_leapfrog_stepper.hpp"

namespace sphark::detail {

// After an event's kicks: the system may remove active particles (StepperOptions::remove_active).
void BlockLeapfrogStepper::remove(Real t, std::vector<std::size_t>& active) {
  if (!opts_.remove_active) return;
  std::optional<StepperOptions::Removal> r = opts_.remove_active(t, w_.data(), active);
  if (!r) return;
  removed_ = true;  // from here on a rollback needs undo_removals
  take(t, *r, active);
}

// The new state of a removal: every per-entry and per-particle array follows the entries'
// sources; `active` keeps its survivors. A particle whose entries have no source (a sink made of
// removed ones) is new: it is evaluated at (t, y), takes its stable step there and joins the
// active set on the deepest of its levels (the next rebin bins it).
void BlockLeapfrogStepper::take(Real t, StepperOptions::Removal& r, std::vector<std::size_t>& active) {
  const std::size_t n_old = n_;
  const std::vector<std::size_t> owner_old = owner_;
  reindex();
  if (r.y.size() != n_ || r.entry_source.size() != n_ || n_ > n_old)
    throw std::logic_error("remove_active: " + std::to_string(r.y.size()) + " values and " +
                           std::to_string(r.entry_source.size()) + " sources for a system of " + std::to_string(n_) +
                           " entries (before: " + std::to_string(n_old) + ")");
  constexpr std::size_t kNone = ~std::size_t{0}, kUnseen = kNone - 1;
  std::vector<std::size_t> source(entries_.size(), kUnseen);  // new particle -> old particle (kNone: new)
  for (std::size_t k = 0; k < n_; ++k) {
    const std::size_t e = r.entry_source[k];
    if (e != kNone && e >= n_old) throw std::logic_error("remove_active: entry source out of range");
    const std::size_t from = e == kNone ? kNone : owner_old[e];
    std::size_t& p = source[owner_[k]];
    if (p != kUnseen && p != from) throw std::logic_error("remove_active: a particle made of two");
    p = from;
  }
  const auto follow = [&](std::vector<Real>& a, bool new_from_y) {
    std::vector<Real> b(n_);
    for (std::size_t k = 0; k < n_; ++k) {
      const std::size_t e = r.entry_source[k];
      b[k] = e != kNone ? a[e] : new_from_y ? r.y[k] : 0;
    }
    a.swap(b);
  };
  follow(dy_, false);
  follow(eval_, true);
  w_ = std::move(r.y);
  out_.assign(n_, 0);
  std::vector<char> was_active(level_.size(), 0);
  int deepest = 0;
  for (std::size_t i : active) was_active[i] = 1, deepest = std::max(deepest, level_[i]);
  std::vector<int> level(source.size(), deepest);
  std::vector<std::int64_t> start(source.size(), 0);
  std::vector<Real> stable(source.size(), 0);
  std::vector<std::size_t> newcomers;
  active.clear();
  for (std::size_t p = 0; p < source.size(); ++p) {
    if (source[p] == kNone) {
      newcomers.push_back(p), active.push_back(p);
      continue;
    }
    level[p] = level_[source[p]], start[p] = start_[source[p]], stable[p] = stable_[source[p]];
    if (was_active[source[p]]) active.push_back(p);
  }
  level_.swap(level), start_.swap(start), stable_.swap(stable);
  if (newcomers.empty()) return;
  evaluate(t, newcomers);
  update_stable_steps(t, newcomers);
}

}  // namespace sphark::detail
