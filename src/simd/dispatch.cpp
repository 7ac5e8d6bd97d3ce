#include "sphark/simd/dispatch.hpp"

#include <atomic>
#include <cstdlib>
#include <cstring>

#include "sphark/simd/lanes.hpp"

namespace sphark {

namespace {
constexpr int kUndecided = -1;
std::atomic<int> in_use{kUndecided};

PairLoopSimd widest() {
#if defined(SPHARK_SIMD_HAVE_AVX2)
  const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  if (avx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512vl"))
    return PairLoopSimd::Avx512;
  if (avx2) return PairLoopSimd::Avx2;
#endif
#if defined(__SSE2__)
  return PairLoopSimd::Sse2;
#else
  return PairLoopSimd::Scalar;
#endif
}

PairLoopSimd capped(PairLoopSimd want) {
  const PairLoopSimd w = widest();
  return static_cast<int>(want) < static_cast<int>(w) ? want : w;
}

PairLoopSimd from_environment() {
  const char* s = std::getenv("SPHARK_SIMD");
  if (s == nullptr) return widest();
  if (std::strcmp(s, "scalar") == 0) return PairLoopSimd::Scalar;
  if (std::strcmp(s, "sse2") == 0) return capped(PairLoopSimd::Sse2);
  if (std::strcmp(s, "avx2") == 0) return capped(PairLoopSimd::Avx2);
  return widest();
}
}  // namespace

PairLoopSimd widest_pair_loop_simd() { return widest(); }

PairLoopSimd pair_loop_simd() {
  int s = in_use.load(std::memory_order_relaxed);
  if (s == kUndecided) {
    s = static_cast<int>(from_environment());
    in_use.store(s, std::memory_order_relaxed);
  }
  return static_cast<PairLoopSimd>(s);
}

PairLoopSimd use_pair_loop_simd(PairLoopSimd want) {
  const PairLoopSimd s = capped(want);
  in_use.store(static_cast<int>(s), std::memory_order_relaxed);
  return s;
}

std::string_view pair_loop_simd_name(PairLoopSimd s) {
  switch (s) {
    case PairLoopSimd::Scalar: return "scalar";
    case PairLoopSimd::Sse2: return "sse2";
    case PairLoopSimd::Avx2: return "avx2";
    case PairLoopSimd::Avx512: return "avx512";
  }
  return "unknown";
}

}  // namespace sphark
