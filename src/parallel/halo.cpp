#include "sphark/parallel/halo.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace sphark {

void check_key_ids(const std::vector<std::int64_t>& ids, const char* who) {
  for (const std::int64_t id : ids)
    if (id < 0 || id > std::int64_t(std::numeric_limits<std::uint32_t>::max()))
      throw std::invalid_argument(std::string(who) + ": global id " + std::to_string(id) + " outside [0, 2^32)");
}
namespace {

constexpr Real kInf = std::numeric_limits<Real>::infinity();
constexpr Real kMargin = 1 + 1e-10;  // relative safety margin of the distance test

template <int D>
Real box_distance2(const Vec<D>& p, const Real* lo, const Real* hi) {
  Real d2 = 0;
  for (int k = 0; k < D; ++k) {
    const Real d = std::max({lo[k] - p[k], p[k] - hi[k], Real(0)});
    d2 += d * d;
  }
  return d2;
}

// Image shifts (one per combination of -2L, -L, 0, +L, +2L on the periodic axes: the ranks'
// coordinates lie in [lo, lo + 2L), compact_periodic_coordinates, so two of them differ by less
// than 2L).
template <int D>
std::vector<Vec<D>> image_shifts(const std::optional<PeriodicBox<D>>& box) {
  std::vector<Vec<D>> shifts{Vec<D>::Zero()};
  for (int k = 0; k < D; ++k) {
    if (!(box && box->periodic[k])) continue;
    const std::size_t m = shifts.size();
    for (int multiple : {-2, -1, 1, 2})
      for (std::size_t j = 0; j < m; ++j) {
        Vec<D> s = shifts[j];
        s[k] += multiple * (box->hi[k] - box->lo[k]);
        shifts.push_back(s);
      }
  }
  return shifts;
}

// Along each periodic axis, the wrapped coordinates xw of this rank's particles moved by a period
// below a pivot in the largest gap between them (found on 4096 bins of the period), when that
// makes their interval shorter: a rank whose particles straddle the periodic face (one crossed it
// since the last migration) keeps a compact box reaching past hi instead of one spanning the
// whole period. The box and the particles' coordinates stay in the same representation; other
// ranks' images are tested in both directions (candidates()).
template <int D>
void compact_periodic_coordinates(std::vector<Real>& xw, std::size_t n, const std::optional<PeriodicBox<D>>& box) {
  constexpr int kBins = 4096;
  std::vector<char> occupied(kBins);
  for (int k = 0; box && k < D; ++k) {
    if (!box->periodic[k] || n == 0) continue;
    const Real lo_box = box->lo[k], period = box->hi[k] - lo_box;
    std::fill(occupied.begin(), occupied.end(), 0);
    for (std::size_t i = 0; i < n; ++i)
      occupied[std::clamp(static_cast<int>((xw[D * i + k] - lo_box) / period * kBins), 0, kBins - 1)] = 1;
    int best_start = -1, best_length = 0;  // the longest circular run of empty bins
    for (int start = 0; start < kBins; ++start) {
      if (occupied[start] || !occupied[(start + kBins - 1) % kBins]) continue;  // runs start after an occupied bin
      int length = 0;
      while (length < kBins && !occupied[(start + length) % kBins]) ++length;
      if (length > best_length) best_start = start, best_length = length;
    }
    if (best_start < 0) continue;  // every bin occupied, or none empty after an occupied one
    Real pivot = lo_box + period * (best_start + 0.5 * best_length) / kBins;  // the gap's middle
    if (pivot >= lo_box + period) pivot -= period;  // (a gap across the face): coordinates in [lo, lo + 2 period)
    Real lo = kInf, hi = -kInf, lo_moved = kInf, hi_moved = -kInf;
    auto moved = [&](Real v) { return v < pivot ? v + period : v; };
    for (std::size_t i = 0; i < n; ++i) {
      const Real v = xw[D * i + k];
      lo = std::min(lo, v), hi = std::max(hi, v);
      lo_moved = std::min(lo_moved, moved(v)), hi_moved = std::max(hi_moved, moved(v));
    }
    if (!(hi_moved - lo_moved < hi - lo)) continue;
    for (std::size_t i = 0; i < n; ++i) xw[D * i + k] = moved(xw[D * i + k]);
  }
}

// Per rank: [lo (D), hi (D), r_max] of its particles (xw); empty ranks have lo > hi.
template <int D>
std::vector<Real> gather_bounds(const Communicator& comm, const std::vector<Real>& xw, const Real* r, std::size_t n) {
  Real mine[2 * D + 1];
  for (int k = 0; k < D; ++k) mine[k] = kInf, mine[D + k] = -kInf;
  mine[2 * D] = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < D; ++k) {
      mine[k] = std::min(mine[k], xw[D * i + k]);
      mine[D + k] = std::max(mine[D + k], xw[D * i + k]);
    }
    mine[2 * D] = std::max(mine[2 * D], r[i]);
  }
  return comm.allgather(mine, 2 * D + 1);
}

template <int D>
struct Candidate {  // a rank that may need some of my particles, with the image shifts to test
  int rank;
  std::vector<Vec<D>> shifts;
};

// Stride of gather_bounds' rows: lo (D), hi (D), r_max.
template <int D>
constexpr std::size_t kRow = 2 * D + 1;

// The (rank, image) pairs where the box of my particles, shifted, comes within reach of theirs.
template <int D>
std::vector<Candidate<D>> candidates(const std::vector<Real>& bounds, int self, int ranks, std::size_t n, Real skin,
                                     const std::vector<Vec<D>>& shifts) {
  const Real* me = bounds.data() + kRow<D> * self;
  std::vector<Candidate<D>> out;
  for (int p = 0; p < ranks && n > 0; ++p) {
    const Real* b = bounds.data() + kRow<D> * p;
    if (p == self || b[0] > b[D]) continue;
    const Real reach = (std::max(me[2 * D], b[2 * D]) + skin) * kMargin;
    Candidate<D> c{p, {}};
    for (const Vec<D>& s : shifts) {
      Real d2 = 0;  // box-box distance
      for (int k = 0; k < D; ++k) {
        const Real d = std::max({b[k] - (me[D + k] + s[k]), (me[k] + s[k]) - b[D + k], Real(0)});
        d2 += d * d;
      }
      if (d2 < reach * reach) c.shifts.push_back(s);
    }
    if (!c.shifts.empty()) out.push_back(std::move(c));
  }
  return out;
}

// For every candidate, the local particles (ascending) some image of which lies within
// max(r_i, r_max(p)) + skin of p's box; each at most once.
template <int D>
std::vector<std::vector<std::uint32_t>> send_lists(const std::vector<Real>& xw, const Real* r, std::size_t n,
                                                   const std::vector<Real>& bounds,
                                                   const std::vector<Candidate<D>>& near, Real skin) {
  std::vector<std::vector<std::uint32_t>> lists(near.size());
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<D> xi = Eigen::Map<const Vec<D>>(xw.data() + D * i);
    for (std::size_t c = 0; c < near.size(); ++c) {
      const Real* b = bounds.data() + kRow<D> * near[c].rank;
      const Real reach = (std::max(r[i], b[2 * D]) + skin) * kMargin;
      for (const Vec<D>& s : near[c].shifts)
        if (box_distance2<D>(xi + s, b, b + D) < reach * reach) {
          lists[c].push_back(static_cast<std::uint32_t>(i));
          break;
        }
    }
  }
  return lists;
}

}  // namespace

template <int D>
HaloPlan<D>::HaloPlan(Communicator comm, std::optional<PeriodicBox<D>> box) : comm_(std::move(comm)), box_(std::move(box)) {}

template <int D>
void HaloPlan<D>::build(const Real* x, const Real* r, const std::int64_t* ids, std::size_t n, Real skin) {
  const int ranks = comm_.size(), self = comm_.rank();
  local_ = n;
  skin_ = skin;
  std::vector<Real> xw(x, x + D * n);
  if (box_ && box_->any_periodic()) box_->wrap_all(x, n, xw.data());
  compact_periodic_coordinates<D>(xw, n, box_);
  const std::vector<Real> bounds = gather_bounds<D>(comm_, xw, r, n);
  Real r_global = 0;
  for (int p = 0; p < ranks; ++p) r_global = std::max(r_global, bounds[(2 * D + 1) * p + 2 * D]);
  for (int k = 0; box_ && k < D; ++k)
    if (box_->periodic[k] && box_->hi[k] - box_->lo[k] < 2 * (r_global + skin))  // same verdict on every rank
      throw CollectiveError("HaloPlan: periodic length " + std::to_string(box_->hi[k] - box_->lo[k]) + " along axis " +
                            std::to_string(k) + " is below 2 (r_max + skin) = " + std::to_string(2 * (r_global + skin)));
  const std::vector<Candidate<D>> near = candidates<D>(bounds, self, ranks, n, skin, image_shifts(box_));
  const std::vector<std::vector<std::uint32_t>> lists = send_lists<D>(xw, r, n, bounds, near, skin);
  std::vector<std::int64_t> counts(ranks, 0);
  send_ranks_.clear();
  send_start_.assign(1, 0);
  send_index_.clear();
  for (std::size_t c = 0; c < near.size(); ++c) {
    if (lists[c].empty()) continue;
    counts[near[c].rank] = static_cast<std::int64_t>(lists[c].size());
    send_ranks_.push_back(near[c].rank);
    send_index_.insert(send_index_.end(), lists[c].begin(), lists[c].end());
    send_start_.push_back(send_index_.size());
  }
  const std::vector<std::int64_t> incoming = comm_.alltoall(counts);
  receive_ranks_.clear();
  receive_start_.assign(1, 0);
  for (int p = 0; p < ranks; ++p)
    if (incoming[p] > 0) {
      receive_ranks_.push_back(p);
      receive_start_.push_back(receive_start_.back() + static_cast<std::size_t>(incoming[p]));
    }
  // The halo's global ids (as raw 8-byte values through the Real buffers).
  halo_ids_.resize(receive_start_.back());
  send_buffer_.resize(std::max(send_buffer_.size(), send_index_.size()));
  for (std::size_t k = 0; k < send_index_.size(); ++k) std::memcpy(&send_buffer_[k], &ids[send_index_[k]], sizeof(Real));
  receive_buffer_.resize(std::max(receive_buffer_.size(), halo_ids_.size()));
  exchange_bytes(1);
  if (!halo_ids_.empty())
    std::memcpy(halo_ids_.data(), receive_buffer_.data(), halo_ids_.size() * sizeof(std::int64_t));
  x_built_.assign(x, x + D * n);
  r_built_.assign(r, r + n);
  stats_.send_partners = static_cast<int>(send_ranks_.size());
  stats_.receive_partners = static_cast<int>(receive_ranks_.size());
  stats_.sent = send_index_.size();
  stats_.received = halo_ids_.size();
  ++stats_.builds;
}

// One message per partner: send_buffer_ (width values per sent particle) to receive_buffer_.
template <int D>
void HaloPlan<D>::exchange_bytes(std::size_t width) {
  sends_.resize(send_ranks_.size());
  receives_.resize(receive_ranks_.size());
  for (std::size_t k = 0; k < send_ranks_.size(); ++k)
    sends_[k] = {send_ranks_[k], send_buffer_.data() + width * send_start_[k],
                 width * (send_start_[k + 1] - send_start_[k]) * sizeof(Real)};
  for (std::size_t k = 0; k < receive_ranks_.size(); ++k)
    receives_[k] = {receive_ranks_[k], receive_buffer_.data() + width * receive_start_[k],
                    width * (receive_start_[k + 1] - receive_start_[k]) * sizeof(Real)};
  comm_.exchange(sends_, receives_);
  ++stats_.exchanges;
}

template <int D>
void HaloPlan<D>::exchange(Real* field, int components) {
  exchange({Field{field, components}});
}

template <int D>
void HaloPlan<D>::exchange(std::span<const Field> fields) {
  split_.clear();
  for (const Field& f : fields) split_.push_back({f.data, f.data + local_ * f.components, f.components});
  exchange(std::span<const SplitField>(split_));
}

template <int D>
void HaloPlan<D>::exchange(std::span<const SplitField> fields) {
  std::size_t width = 0;
  for (const SplitField& f : fields) width += static_cast<std::size_t>(f.components);
  if (send_buffer_.size() < width * send_index_.size()) send_buffer_.resize(width * send_index_.size());
  if (receive_buffer_.size() < width * halo()) receive_buffer_.resize(width * halo());
  for (std::size_t k = 0; k < send_index_.size(); ++k) {
    Real* out = send_buffer_.data() + width * k;
    for (const SplitField& f : fields)
      for (int c = 0; c < f.components; ++c) *out++ = f.local[send_index_[k] * f.components + c];
  }
  exchange_bytes(width);
  for (std::size_t k = 0; k < halo(); ++k) {
    const Real* in = receive_buffer_.data() + width * k;
    for (const SplitField& f : fields)
      for (int c = 0; c < f.components; ++c) f.halo[k * f.components + c] = *in++;
  }
}

template <int D>
bool HaloPlan<D>::still_valid(const Real* x, const Real* r) const {
  Real moved2 = 0, grown = 0;  // (squared displacements: one square root)
  for (std::size_t i = 0; i < local_; ++i) {
    Vec<D> d = Eigen::Map<const Vec<D>>(x + D * i) - Eigen::Map<const Vec<D>>(x_built_.data() + D * i);
    if (box_) d = box_->minimum_image(d);
    moved2 = std::max(moved2, d.squaredNorm());
    grown = std::max(grown, r[i] - r_built_[i]);
  }
  return comm_.allreduce(2 * std::sqrt(moved2) + grown, ReduceOp::Max) <= skin_;
}

template class HaloPlan<1>;
template class HaloPlan<2>;
template class HaloPlan<3>;

}  // namespace sphark
