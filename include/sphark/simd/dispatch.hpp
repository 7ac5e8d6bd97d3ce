#pragma once
// Which vector path the pair loops take (WCSPH, SPMHD forces and h solve), chosen at run time:
//   avx512  four lanes compiled for AVX-512 F/DQ/VL + FMA: 256-bit vectors with 32 vector registers
//           (fewer spills of the pair loops' sums: WCSPH 8-15 % faster than avx2 on this machine;
//           eight lanes of 512 bits measured 1.5x slower) - the default where the CPU has them
//   avx2    four lanes, AVX2 + FMA (CPUs that have both; the default there without AVX-512)
//   sse2    two lanes, the x86-64 baseline (every x86-64 CPU; the default without AVX2)
//   scalar  one pair at a time: the reference path the others are tested against
// The environment variable SPHARK_SIMD=scalar|sse2|avx2|avx512 (read once) chooses a narrower path;
// use_pair_loop_simd() changes it (tests). Paths differ at round-off only: the lanes sum in
// another order, and FMA rounds a*b+c once (tests/simd compares them field by field).
#include <string_view>

namespace sphark {

enum class PairLoopSimd { Scalar, Sse2, Avx2, Avx512 };

// The path in use now.
PairLoopSimd pair_loop_simd();
// Asks for `want`; returns the path in use afterwards (the widest the CPU has that is <= want).
PairLoopSimd use_pair_loop_simd(PairLoopSimd want);
// The widest path this CPU and build have.
PairLoopSimd widest_pair_loop_simd();
std::string_view pair_loop_simd_name(PairLoopSimd s);
// Lanes of the path: 1, 2, 4.
constexpr int simd_lanes(PairLoopSimd s) {
  return s == PairLoopSimd::Avx512 || s == PairLoopSimd::Avx2 ? 4 : s == PairLoopSimd::Sse2 ? 2 : 1;
}

}  // namespace sphark
