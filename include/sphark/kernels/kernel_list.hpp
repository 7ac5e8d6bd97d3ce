#pragma once
// The one list of smoothing kernels. Adding a kernel is its shape in kernels.hpp (an alias
// template K<D> = RadialKernel<D, Shape>) plus one entry X(K) in SPHARK_KERNELS below; what
// follows from the list:
//   - every scheme's explicit instantiations:  SPHARK_KERNELS(MY_INSTANTIATION) in its .cpp,
//     where MY_INSTANTIATION(K) instantiates the scheme for K<2> and K<3>;
//   - the run-time choice by name (--kernel):  with_kernel<D>(name, f), kernel_names<D>();
//   - the kernel tests and benchmarks (typed over KernelList<D>, or SPHARK_KERNELS).
// (Explicit instantiations must name their types, hence the X-macro; the type list is built from
// the same macro, so the two cannot disagree.)
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "sphark/kernels/kernels.hpp"

// X(K) for every kernel alias template K of kernels.hpp.
#define SPHARK_KERNELS(X) X(CubicSpline) X(QuinticSpline) X(WendlandC2) X(WendlandC4) X(WendlandC6)

namespace sphark {

template <class... K>
struct KernelTypes {
  static constexpr std::size_t size = sizeof...(K);
};

namespace kernel_detail {
template <class List>
struct DropFirst;
template <class First, class... K>
struct DropFirst<KernelTypes<First, K...>> {
  using type = KernelTypes<K...>;
};
}  // namespace kernel_detail

// KernelTypes<CubicSpline<D>, QuinticSpline<D>, ...>, in the order of SPHARK_KERNELS.
#define SPHARK_KERNEL_LIST_ENTRY(K) , K<D>
template <int D>
using KernelList = typename kernel_detail::DropFirst<KernelTypes<void SPHARK_KERNELS(SPHARK_KERNEL_LIST_ENTRY)>>::type;
#undef SPHARK_KERNEL_LIST_ENTRY

// A kernel type passed by value to a generic lambda: [](auto tag) { using K = typename decltype(tag)::type; }.
template <class K>
struct KernelTag {
  using type = K;
};

// The command-line names (K::name) of the kernels, in list order.
template <int D>
std::vector<std::string> kernel_names() {
  auto names = []<class... K>(KernelTypes<K...>) { return std::vector<std::string>{std::string(K::name)...}; };
  return names(KernelList<D>{});
}

namespace kernel_detail {
template <int D, class F, class First, class... Rest>
decltype(auto) dispatch(std::string_view name, F& f, KernelTypes<First, Rest...>) {
  if (name == First::name) return f(KernelTag<First>{});
  if constexpr (sizeof...(Rest) > 0) {
    return dispatch<D>(name, f, KernelTypes<Rest...>{});
  } else {
    std::string known;
    for (const std::string& n : kernel_names<D>()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown kernel '" + std::string(name) + "' (known: " + known + ")");
  }
}
}  // namespace kernel_detail

// f(KernelTag<K>{}) for the kernel K of KernelList<D> called `name` (every call must return the
// same type); throws std::invalid_argument naming the known kernels when there is none.
template <int D, class F>
decltype(auto) with_kernel(std::string_view name, F&& f) {
  return kernel_detail::dispatch<D>(name, f, KernelList<D>{});
}

}  // namespace sphark
