// ARKODE's weighted RMS norm, summed so that the result depends only on the set of terms, not
// on their order nor on how they are split over the ranks (sundials_vector.hpp).
//
//   ||x||_w = A sqrt( sum_i q_i^2 / N ),   a_i = |x_i w_i|,  A = max_i a_i,  q_i = a_i (1 / A),
//
// with A the global maximum (one Allreduce) and every q_i^2 in [0, 1] added as a fixed-point
// number of 127 fractional bits (two unsigned 64-bit words, 63 + 64 bits; the bits below are
// dropped, the same way wherever the term is summed). The integer sums are exact: their
// 32-bit limbs are summed over the ranks (one Allreduce) and the total is rounded to a double
// once, by the same steps on every rank. Non-finite terms give NaN (any NaN) or +inf.
#include <cmath>
#include <cstdint>
#include <limits>

#include <nvector/nvector_serial.h>

#include "mpi_backend.hpp"
#include "sphark/parallel/sundials_vector.hpp"

namespace sphark {
namespace {

using u128 = unsigned __int128;
constexpr int kLimbs = 8;  // 4 x 32 bits of each 128-bit accumulator

std::size_t local_length(N_Vector v) {
  return N_VGetVectorID(v) == SUNDIALS_NVEC_PARALLEL ? detail::parallel_local_length(v)
                                                     : static_cast<std::size_t>(N_VGetLength(v));
}

// sum_i q_i^2 (q_i = a_i / scale) as the exact integer hi 2^64 + lo in units of 2^-127,
// returned as 32-bit limbs, least significant first (hi's limbs after lo's).
template <class Term>
void fixed_point_sum(std::size_t n, Term&& a, double scale, std::int64_t* limbs) {
  constexpr double k2p63 = 9223372036854775808.0, k2p64 = 18446744073709551616.0;
  const double inverse = 1.0 / scale;  // the same on every rank: q_i depends on a_i only
  u128 hi = 0, lo = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double q = a(i) * inverse;
    const double f = (q * q) * k2p63;                // exact scaling of the rounded square, < 2^64
    const auto whole = static_cast<std::uint64_t>(f);  // floor (f >= 0)
    hi += whole;
    lo += static_cast<std::uint64_t>((f - static_cast<double>(whole)) * k2p64);  // exact remainder < 1
  }
  for (int k = 0; k < 4; ++k) {
    limbs[k] = static_cast<std::int64_t>((lo >> (32 * k)) & 0xffffffffu);
    limbs[4 + k] = static_cast<std::int64_t>((hi >> (32 * k)) & 0xffffffffu);
  }
}

// The limbs' total (value sum_k limb_k 2^(32k) 2^-127 with hi offset by 2^64) as a double:
// carries propagated, then the limbs added from the most significant (deterministic).
double limbs_value(std::int64_t* limbs) {
  std::uint64_t digit[kLimbs + 3] = {};
  u128 carry = 0;
  for (int k = 0; k < kLimbs + 3; ++k) {
    // lo limbs k = 0..3 at 2^(32k); hi limbs at 2^(64 + 32k): positions 2..5 of the digits.
    u128 v = carry;
    if (k < 4) v += static_cast<std::uint64_t>(limbs[k]);
    if (k >= 2 && k < 6) v += static_cast<std::uint64_t>(limbs[4 + k - 2]);
    digit[k] = static_cast<std::uint64_t>(v & 0xffffffffu);
    carry = v >> 32;
  }
  double value = 0;
  for (int k = kLimbs + 2; k >= 0; --k) value += std::ldexp(static_cast<double>(digit[k]), 32 * k - 127);
  return value;
}

template <class Term>
double reproducible_rms(N_Vector x, std::size_t n, Term&& a) {
  void* comm = N_VGetCommunicator(x);
  double range[3] = {0, 0, 0};  // max a_i, any NaN, any inf
  for (std::size_t i = 0; i < n; ++i) {
    const double v = a(i);
    if (std::isnan(v)) range[1] = 1;
    else if (std::isinf(v)) range[2] = 1;
    else range[0] = std::max(range[0], v);
  }
  detail::raw_allreduce(comm, range, 3, ReduceOp::Max);
  if (range[1] > 0) return std::numeric_limits<double>::quiet_NaN();
  if (range[2] > 0) return std::numeric_limits<double>::infinity();
  if (range[0] == 0) return 0;
  std::int64_t limbs[kLimbs];
  fixed_point_sum(n, a, range[0], limbs);
  detail::raw_allreduce(comm, limbs, kLimbs, ReduceOp::Sum);
  return range[0] * std::sqrt(limbs_value(limbs) / static_cast<double>(N_VGetLength(x)));
}

// N_Vector ops (C callbacks: nothing here throws).
realtype wrms_norm(N_Vector x, N_Vector w) {
  const double* xv = N_VGetArrayPointer(x);
  const double* wv = N_VGetArrayPointer(w);
  return reproducible_rms(x, local_length(x), [&](std::size_t i) { return std::abs(xv[i] * wv[i]); });
}

realtype wrms_norm_mask(N_Vector x, N_Vector w, N_Vector id) {
  const double* xv = N_VGetArrayPointer(x);
  const double* wv = N_VGetArrayPointer(w);
  const double* mv = N_VGetArrayPointer(id);
  return reproducible_rms(x, local_length(x), [&](std::size_t i) { return mv[i] > 0 ? std::abs(xv[i] * wv[i]) : 0.0; });
}

}  // namespace

void make_norms_reproducible(N_Vector v) {
  v->ops->nvwrmsnorm = &wrms_norm;
  v->ops->nvwrmsnormmask = &wrms_norm_mask;
}

}  // namespace sphark
