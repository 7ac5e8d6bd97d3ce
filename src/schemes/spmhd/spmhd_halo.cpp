#include "spmhd_halo.hpp"

#include <limits>
#include <stdexcept>
#include <string>

namespace sphark::spmhd_detail {

template <int D>
void Halo<D>::set_particles(std::vector<std::int64_t> ids) {
  check_key_ids(ids, "SpmhdScheme");
  ids_ = std::move(ids);
  built_ = false;
}

// docs/scaling.md, "The API a scheme uses", step 1.
template <int D>
bool Halo<D>::update_plan(const Real* xs, const std::vector<Real>& r, Real skin_fraction) {
  if (built_ && plan_.still_valid(xs, r.data())) return false;
  Real sums[2] = {0, static_cast<Real>(local())};
  for (std::size_t a = 0; a < local(); ++a) sums[0] += r[a];
  comm_.allreduce(sums, 2, ReduceOp::Sum);
  const Real skin = sums[1] > 0 ? skin_fraction * sums[0] / sums[1] : 0;
  plan_.build(xs, r.data(), ids_.data(), local(), skin);
  built_ = true;
  keys_.resize(all());
  for (std::size_t a = 0; a < local(); ++a) keys_[a] = static_cast<std::uint32_t>(ids_[a]);
  for (std::size_t k = 0; k < plan_.halo(); ++k) keys_[local() + k] = static_cast<std::uint32_t>(plan_.halo_ids()[k]);
  return true;
}

template <int D>
void Halo<D>::exchange_state(const Real* y, const StateLayout& L, const std::vector<Real>& masses,
                             const std::vector<Real>& r) {
  const std::size_t n = local(), all = this->all();
  auto load = [&](std::vector<Real>& to, const Real* from, int width) {
    to.assign(from, from + width * n);
    to.resize(width * all);
  };
  std::vector<typename HaloPlan<D>::Field> fields;
  auto add = [&](std::vector<Real>& to, const Real* from, int width) {
    load(to, from, width);
    fields.push_back({to.data(), width});
  };
  add(x, y + L.offset(Field::Position), D);
  add(v, y + L.offset(Field::Velocity), D);
  if (L.has(Field::InternalEnergy)) add(u, y + L.offset(Field::InternalEnergy), 1);
  add(B, y + L.offset(Field::MagneticField), 3);
  if (L.has(Field::Psi)) add(psi, y + L.offset(Field::Psi), 1);
  add(m, masses.data(), 1);
  add(radius, r.data(), 1);
  plan_.exchange(std::span<const typename HaloPlan<D>::Field>(fields));
  h.resize(all);
  rho.resize(all);
  omega.resize(all);
}

template <int D>
const Real* Halo<D>::field(Field f) const {
  if (f == Field::Position) return x.data();
  if (f == Field::Velocity) return v.data();
  if (f == Field::InternalEnergy) return u.data();
  if (f == Field::MagneticField) return B.data();
  if (f == Field::Psi) return psi.data();
  return nullptr;
}

template class Halo<2>;
template class Halo<3>;

}  // namespace sphark::spmhd_detail
