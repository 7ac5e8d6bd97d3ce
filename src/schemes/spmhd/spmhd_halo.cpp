#include "spmhd_halo.hpp"

#include <span>

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
void Halo<D>::exchange_geometry(const Real* xs, const Real* masses, const Real* r) {
  x.resize(D * halo());
  m.resize(halo());
  radius.resize(halo());
  fields_ = {{xs, x.data(), D}, {masses, m.data(), 1}, {r, radius.data(), 1}};
  plan_.exchange(std::span<const typename HaloPlan<D>::SplitField>(fields_));
}

template <int D>
void Halo<D>::exchange_fields(const Real* y, const StateLayout& L, const std::vector<Real>* local_density) {
  fields_.clear();
  auto add = [&](std::vector<Real>& to, const Real* from, int width) {
    to.resize(width * halo());
    fields_.push_back({from, to.data(), width});
  };
  if (L.has(Field::Velocity)) add(v, y + L.offset(Field::Velocity), D);  // (not for fixed particles)
  if (L.has(Field::InternalEnergy)) add(u, y + L.offset(Field::InternalEnergy), 1);
  add(B, y + L.offset(Field::MagneticField), 3);
  if (L.has(Field::Psi)) add(psi, y + L.offset(Field::Psi), 1);
  if (local_density) add(density, local_density->data(), 3);
  plan_.exchange(std::span<const typename HaloPlan<D>::SplitField>(fields_));
}

template class Halo<2>;
template class Halo<3>;

}  // namespace sphark::spmhd_detail
