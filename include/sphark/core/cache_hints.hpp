#pragma once
// Cache hints of the pair loops' records (issue #19); hints only: no result depends on them.
//
// Prefetch: a row's neighbours lie within its span of slots (NeighbourSearch::row_spans); as the
// rows advance in cell order the span's upper end reaches records written long before (at 10^6
// particles, out of every cache), so the loops fetch the record kPrefetchSlotsAhead slots beyond it.
//
// Streaming stores: records of more than stream_records_above() bytes in all are written past the
// caches (non-temporal stores). The pair loop reads them back only after the rest of the pass has
// evicted them, and an ordinary store that misses first reads the line it overwrites. Measured
// (bench_wcsph_rhs, bench_spmhd_rhs, one thread, docs/performance.md): at 10^6 particles +6 % for
// WCSPH and SPMHD 2D; streaming every record size costs 20 % at 10^3 and 5 % at 10^4 (records
// that would have stayed in cache), hence the threshold, 16 MB by default.
#include <emmintrin.h>

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace sphark {

inline constexpr std::size_t kPrefetchSlotsAhead = 32;

// Every cache line of bytes [p, p + bytes).
inline void prefetch_lines(const void* p, std::size_t bytes) {
  const char* c = static_cast<const char*>(p);
  for (std::size_t o = 0; o < bytes; o += 64) __builtin_prefetch(c + o);
  __builtin_prefetch(c + bytes - 1);
}

// The threshold of streaming stores, process-wide (tests set it to 0 to compare both ways).
inline std::size_t& stream_records_above() {
  static std::size_t bytes = std::size_t(16) << 20;
  return bytes;
}
inline bool stream_records(std::size_t bytes) { return bytes > stream_records_above(); }

// count doubles from src to dst: streamed when `stream` (then count even and dst 16-byte
// aligned, else copied), copied otherwise. After streaming, store_fence() before other threads
// read them (each writing thread, ahead of the barrier that ends its loop).
inline void store_record(double* dst, const double* src, int count, bool stream) {
  if (!stream || count % 2 != 0 || (reinterpret_cast<std::uintptr_t>(dst) & 15) != 0) {
    std::memcpy(dst, src, sizeof(double) * static_cast<std::size_t>(count));
    return;
  }
  for (int k = 0; k < count; k += 2) _mm_stream_pd(dst + k, _mm_load_pd(src + k));
}
inline void store_fence() { _mm_sfence(); }

}  // namespace sphark
