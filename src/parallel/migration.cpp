#include "sphark/parallel/migration.hpp"

#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

namespace sphark {
namespace {

std::uint64_t mix(std::uint64_t z) {  // splitmix64 finaliser: the id checksum sees every bit
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

std::size_t state_width(const ParticleData::FlatState& s) {
  return static_cast<std::size_t>(std::accumulate(s.components.begin(), s.components.end(), 0));
}

// Values per particle in a migration record: the id, then every array, then every state.
std::size_t record_width(const ParticleData& d) {
  std::size_t w = 1;
  for (const auto& a : d.arrays) w += static_cast<std::size_t>(a.components);
  for (const auto& s : d.states) w += state_width(s);
  return w;
}

std::string check_sizes(const ParticleData& d, std::size_t destinations, int ranks, const std::vector<int>* dest) {
  if (!d.ids) return "ParticleData without ids";
  const std::size_t n = d.ids->size();
  if (dest && destinations != n) return std::to_string(destinations) + " destinations for " + std::to_string(n) + " particles";
  for (std::size_t k = 0; k < d.arrays.size(); ++k)
    if (!d.arrays[k].values || d.arrays[k].components < 1 || d.arrays[k].values->size() != n * d.arrays[k].components)
      return "array " + std::to_string(k) + " does not hold components x " + std::to_string(n) + " values";
  for (std::size_t k = 0; k < d.states.size(); ++k)
    if (!d.states[k].values || d.states[k].values->size() != n * state_width(d.states[k]))
      return "state " + std::to_string(k) + " does not hold " + std::to_string(n) + " particles";
  if (dest)
    for (int r : *dest)
      if (r < 0 || r >= ranks) return "destination rank " + std::to_string(r) + " of " + std::to_string(ranks);
  return {};
}

// Value `component` of particle i in the array or state named by ref.
Real value_of(const ParticleData& d, const ParticleData::Ref& ref, std::size_t i, int component) {
  if (ref.array >= 0) {
    const auto& a = d.arrays[ref.array];
    return (*a.values)[i * a.components + component];
  }
  const auto& s = d.states[ref.state];
  const std::size_t n = d.ids->size();
  std::size_t offset = 0;
  for (int f = 0; f < ref.field; ++f) offset += n * s.components[f];
  return (*s.values)[offset + i * s.components[ref.field] + component];
}

// Record of particle i appended to out.
void pack(const ParticleData& d, std::size_t i, std::vector<Real>& out) {
  out.push_back(std::bit_cast<Real>((*d.ids)[i]));
  for (const auto& a : d.arrays)
    for (int c = 0; c < a.components; ++c) out.push_back((*a.values)[i * a.components + c]);
  const std::size_t n = d.ids->size();
  for (const auto& s : d.states) {
    std::size_t offset = 0;
    for (int comps : s.components) {
      for (int c = 0; c < comps; ++c) out.push_back((*s.values)[offset + i * comps + c]);
      offset += n * comps;
    }
  }
}

// Rebuilds every array of d from records (kept particles first, then received).
void unpack(ParticleData& d, const std::vector<Real>& records, std::size_t n) {
  const std::size_t width = record_width(d);
  std::vector<std::int64_t> ids(n);
  for (std::size_t i = 0; i < n; ++i) ids[i] = std::bit_cast<std::int64_t>(records[i * width]);
  *d.ids = std::move(ids);
  std::size_t col = 1;
  for (auto& a : d.arrays) {
    std::vector<Real> v(n * a.components);
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < a.components; ++c) v[i * a.components + c] = records[i * width + col + c];
    *a.values = std::move(v);
    col += a.components;
  }
  for (auto& s : d.states) {
    std::vector<Real> v(n * state_width(s));
    std::size_t offset = 0;
    for (int comps : s.components) {
      for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < comps; ++c) v[offset + i * comps + c] = records[i * width + col + c];
      offset += n * comps;
      col += comps;
    }
    *s.values = std::move(v);
  }
}

void compare(const Communicator& comm, const ConservedTotals& before, const ConservedTotals& after, int dim) {
  std::string error;
  if (after.count != before.count)
    error = "particle count " + std::to_string(before.count) + " became " + std::to_string(after.count);
  else if (after.id_sum != before.id_sum || after.id_hash != before.id_hash)
    error = "the set of particle ids changed";
  const Real bound = 2 * Real(before.count + comm.size()) * std::numeric_limits<Real>::epsilon();
  if (error.empty() && std::abs(after.mass - before.mass) > bound * before.abs_mass)
    error = "total mass changed by " + std::to_string(after.mass - before.mass);
  for (int c = 0; c < dim && error.empty(); ++c)
    if (std::abs(after.momentum[c] - before.momentum[c]) > bound * before.abs_momentum[c])
      error = "momentum component " + std::to_string(c) + " changed by " + std::to_string(after.momentum[c] - before.momentum[c]);
  if (!error.empty()) error = "migration: " + error;
  comm.check(error.empty(), error);  // all ranks compute the same totals: all throw together
}

}  // namespace

ConservedTotals conserved_totals(const Communicator& comm, const ParticleData& d) {
  const std::string bad = check_sizes(d, 0, comm.size(), nullptr);
  comm.check(bad.empty(), "conserved_totals: " + bad);
  const std::size_t n = d.ids->size();
  std::int64_t local[3] = {static_cast<std::int64_t>(n), 0, 0};
  std::uint64_t sum = 0, hash = 0;
  for (std::int64_t id : *d.ids) sum += static_cast<std::uint64_t>(id), hash += mix(static_cast<std::uint64_t>(id));
  local[1] = std::bit_cast<std::int64_t>(sum);
  local[2] = std::bit_cast<std::int64_t>(hash);
  ConservedTotals t;
  const std::vector<std::int64_t> all = comm.allgather(local, 3);  // combined with wrap-around below
  for (int r = 0; r < comm.size(); ++r) {
    t.count += all[3 * r];
    t.id_sum += static_cast<std::uint64_t>(all[3 * r + 1]);
    t.id_hash += static_cast<std::uint64_t>(all[3 * r + 2]);
  }
  if (d.mass.array < 0 && d.mass.state < 0) return t;
  Real sums[8] = {0, 0, 0, 0, 0, 0, 0, 0};  // mass, |mass|, momentum[3], |momentum|[3]
  const bool has_v = d.velocity.array >= 0 || d.velocity.state >= 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Real m = value_of(d, d.mass, i, 0);
    sums[0] += m;
    sums[1] += std::abs(m);
    for (int c = 0; has_v && c < d.dim && c < 3; ++c) {
      const Real p = m * value_of(d, d.velocity, i, c);
      sums[2 + c] += p;
      sums[5 + c] += std::abs(p);
    }
  }
  comm.allreduce(sums, 8, ReduceOp::Sum);
  t.mass = sums[0];
  t.abs_mass = sums[1];
  for (int c = 0; c < 3; ++c) t.momentum[c] = sums[2 + c], t.abs_momentum[c] = sums[5 + c];
  return t;
}

MigrationStats migrate(const Communicator& comm, const std::vector<int>& destination, ParticleData& d) {
  const std::string bad = check_sizes(d, destination.size(), comm.size(), &destination);
  comm.check(bad.empty(), "migrate: " + bad);
  const bool checked = d.mass.array >= 0 || d.mass.state >= 0;
  const ConservedTotals before = conserved_totals(comm, d);
  const std::size_t n = d.ids->size(), width = record_width(d);
  const int self = comm.rank(), ranks = comm.size();
  // Records grouped by destination (rank order), the kept ones first in `records`.
  std::vector<std::int64_t> send_count(ranks, 0);
  for (int r : destination) ++send_count[r];
  std::vector<std::size_t> start(ranks + 1, 0);
  for (int r = 0; r < ranks; ++r) start[r + 1] = start[r] + (r == self ? 0 : send_count[r]) * width;
  std::vector<std::size_t> next(ranks + 1, 0), order(n);  // counting sort by destination, stable
  for (int r = 0; r < ranks; ++r) next[r + 1] = next[r] + send_count[r];
  for (std::size_t i = 0; i < n; ++i) order[next[destination[i]]++] = i;
  std::vector<Real> outgoing, records;
  outgoing.reserve(start[ranks]);
  records.reserve(send_count[self] * width);
  for (std::size_t i : order) pack(d, i, destination[i] == self ? records : outgoing);
  std::vector<std::int64_t> counts = send_count;
  counts[self] = 0;
  const std::vector<std::int64_t> receive_count = comm.alltoall(counts);
  MigrationStats stats;
  std::vector<Communicator::Send> sends;
  for (int r = 0; r < ranks; ++r)
    if (counts[r] > 0) {
      sends.push_back({r, outgoing.data() + start[r], (start[r + 1] - start[r]) * sizeof(Real)});
      stats.sent += counts[r];
      ++stats.partners;
    }
  stats.bytes_sent = outgoing.size() * sizeof(Real);
  const std::size_t kept = records.size() / width;
  std::size_t total = kept;
  for (int r = 0; r < ranks; ++r) total += receive_count[r];
  records.resize(total * width);
  std::vector<Communicator::Receive> receives;
  std::size_t at = kept * width;
  for (int r = 0; r < ranks; ++r)
    if (receive_count[r] > 0) {
      receives.push_back({r, records.data() + at, receive_count[r] * width * sizeof(Real)});
      at += receive_count[r] * width;
      stats.received += receive_count[r];
    }
  comm.exchange(sends, receives);
  unpack(d, records, total);
  const ConservedTotals after = conserved_totals(comm, d);
  compare(comm, before, after, checked ? d.dim : 0);
  return stats;
}

}  // namespace sphark
