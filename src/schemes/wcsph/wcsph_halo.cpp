#include "wcsph_halo.hpp"

#include <limits>
#include <stdexcept>

namespace sphark::wcsph_detail {

template <int D>
Halo<D>::Halo(Communicator comm, std::optional<PeriodicBox<D>> box) : comm_(comm), plan_(comm, std::move(box)) {}

template <int D>
void Halo<D>::set_particles(std::vector<std::int64_t> ids) {
  check_key_ids(ids, "WcsphSystem");
  ids_ = std::move(ids);
  built_ = false;
}

// docs/scaling.md, RHS step 1: which particles every rank needs, and the keys of local + halo.
template <int D>
void Halo<D>::build_plan(const Real* x, Real skin) {
  const std::size_t n = local();
  plan_.build(x, radius_.data(), ids_.data(), n, skin);
  built_ = true;
  keys_.resize(all());
  for (std::size_t a = 0; a < n; ++a) keys_[a] = static_cast<std::uint32_t>(ids_[a]);
  for (std::size_t k = 0; k < plan_.halo(); ++k) keys_[n + k] = static_cast<std::uint32_t>(plan_.halo_ids()[k]);
}

// docs/scaling.md, RHS steps 1-2.
template <int D>
bool Halo<D>::gather(const Real* y, const StateLayout& L, Real support, Real skin) {
  const std::size_t n = local();
  const ParticleFields<D> s = state_fields<D>(y, L);
  radius_.assign(n, support);
  const bool rebuild = !built_ || !plan_.still_valid(s.x, radius_.data());
  if (rebuild) build_plan(s.x, skin);
  const std::size_t all = this->all();
  auto load = [&](std::vector<Real>& to, const Real* from, std::size_t width) {
    to.assign(from, from + width * n);
    to.resize(width * all);
  };
  load(x_, s.x, D);
  load(v_, s.v, D);
  load(rho_, s.rho, 1);
  psi_field_ = s.psi != nullptr;
  if (psi_field_) {
    load(psi_, s.psi, 1);
    plan_.exchange({{x_.data(), D}, {v_.data(), D}, {rho_.data(), 1}, {psi_.data(), 1}});
  } else {
    plan_.exchange({{x_.data(), D}, {v_.data(), D}, {rho_.data(), 1}});
  }
  return rebuild;
}

template <int D>
ParticleFields<D> Halo<D>::fields() const {
  return {x_.data(), v_.data(), rho_.data(), psi_field_ ? psi_.data() : nullptr};
}

template <int D>
void Halo<D>::exchange(std::vector<Real>& values, int components) {
  values.resize(static_cast<std::size_t>(components) * all());
  plan_.exchange(values.data(), components);
}

template class Halo<2>;
template class Halo<3>;

}  // namespace sphark::wcsph_detail
