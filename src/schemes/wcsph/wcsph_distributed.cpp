// The distributed parts of WcsphSystem (docs/scaling.md, "The API a scheme uses"): the same
// steps as the serial rhs() (wcsph_system.cpp) over local + halo particles, with the halo's
// exchanges between them.
#include <exception>
#include <stdexcept>

#include "sphark/integrate/callback_errors.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/schemes/wcsph/wcsph_system.hpp"
#include "wcsph_halo.hpp"
#include "wcsph_pair_rows.hpp"

namespace sphark {

template <int D, class Kernel>
void WcsphSystem<D, Kernel>::distribute(Communicator comm, std::vector<std::int64_t> ids) {
  halo_ = std::make_unique<wcsph_detail::Halo<D>>(std::move(comm), search_.box());
  set_particles(std::move(ids));
}

template <int D, class Kernel>
void WcsphSystem<D, Kernel>::set_particles(std::vector<std::int64_t> ids) {
  if (!halo_) throw std::logic_error("WcsphSystem::set_particles: the system is not distributed");
  halo_->set_particles(std::move(ids));
  resize_particles(halo_->local());
}

template <int D, class Kernel>
const std::vector<std::int64_t>& WcsphSystem<D, Kernel>::ids() const {
  static const std::vector<std::int64_t> none;
  return halo_ ? halo_->ids() : none;
}

// Collective: <grad rho>^L of the halo particles from their owners, into the halo's records.
template <int D, class Kernel>
void WcsphSystem<D, Kernel>::exchange_gradients() {
  using wcsph_detail::Record;
  const std::size_t n = layout_.particles(), all = halo_->all();
  const std::uint32_t* particle = slot_particle_.data();
  grad_particles_.resize(D * all);
  for (std::size_t a = 0; a < n; ++a)
    for (int k = 0; k < D; ++k) grad_particles_[D * particle[a] + k] = grad_rho_[a][k];
  halo_->exchange(grad_particles_, D);
  for (std::size_t s = n; s < all; ++s)
    for (int k = 0; k < D; ++k)
      records_[Record<D>::size * s + Record<D>::grad_rho + k] = grad_particles_[D * particle[s] + k];
}

// 1-2: the halo plan and the halo's state (collective); 3-4: lists over local + halo, rows by
// global id, and the rows up to the force loop (local); 5: agree on the outcome; 6: the
// halo's density gradients (Antuono's correction only); 7: forces of the local particles.
// A failure returns from every rank at the same step: none waits in an exchange alone.
template <int D, class Kernel>
int WcsphSystem<D, Kernel>::distributed_rhs(const Real* y, Real* ydot) {
  wcsph_detail::Halo<D>& halo = *halo_;
  try {
    const Real support = Kernel::support * p_.h;
    const bool new_halo = halo.gather(y, layout_, support, p_.skin_fraction * support);
    std::string message;
    int code = 0;
    try {
      update_neighbours(halo.fields().x, halo.all(), halo.keys(), new_halo);
      prepare_rows(halo.fields(), halo.all());
    } catch (...) {
      code = -1;
      message = current_exception_message("WcsphSystem::rhs");
    }
    if ((code = halo.agree(code, message)) != 0) {
      error_ = message;
      return code;
    }
    if (corrected_diffusion()) exchange_gradients();
    forces(y, ydot);
  } catch (...) {  // a CollectiveError is thrown on every rank: all return here together
    error_ = current_exception_message("WcsphSystem::rhs");
    return -1;
  }
  evaluated_y_.assign(y, y + layout_.size());
  return 0;
}

#define SPHARK_WCSPH_DISTRIBUTED(K)                                                                  \
  template void WcsphSystem<2, K<2>>::distribute(Communicator, std::vector<std::int64_t>);         \
  template void WcsphSystem<3, K<3>>::distribute(Communicator, std::vector<std::int64_t>);         \
  template void WcsphSystem<2, K<2>>::set_particles(std::vector<std::int64_t>);                    \
  template void WcsphSystem<3, K<3>>::set_particles(std::vector<std::int64_t>);                    \
  template const std::vector<std::int64_t>& WcsphSystem<2, K<2>>::ids() const;                     \
  template const std::vector<std::int64_t>& WcsphSystem<3, K<3>>::ids() const;                     \
  template int WcsphSystem<2, K<2>>::distributed_rhs(const Real*, Real*);                          \
  template int WcsphSystem<3, K<3>>::distributed_rhs(const Real*, Real*);                          \
  template void WcsphSystem<2, K<2>>::exchange_gradients();                                        \
  template void WcsphSystem<3, K<3>>::exchange_gradients();
SPHARK_KERNELS(SPHARK_WCSPH_DISTRIBUTED)
#undef SPHARK_WCSPH_DISTRIBUTED

}  // namespace sphark
