// compare_frames <serial.vtp> <distributed.pvtp>: the same particles with the same values, bit
// for bit. The serial frame's particle a has global id a; the distributed frame's pieces carry
// the ids (Int64 "id"). Exit 0 and "frames equal: ..." if every point and every array of the
// serial frame is found unchanged for every id exactly once; exit 1 with the first difference.
#include <cstdio>
#include <exception>
#include <vector>

#include "sphark/io/vtp_reader.hpp"

using namespace sphark;

namespace {
int differ(const char* what) {
  std::printf("frames differ: %s\n", what);
  return 1;
}

// Is value k of array `name` of serial point a equal to that of distributed point b?
bool equal_points(const VtpContents& s, const VtpContents& d, std::size_t a, std::size_t b) {
  for (int k = 0; k < 3; ++k)
    if (s.points[3 * a + k] != d.points[3 * b + k]) return false;
  for (const VtpArray& arr : s.arrays) {
    const VtpArray* other = d.find(arr.name);
    const std::size_t c = static_cast<std::size_t>(arr.components);
    for (std::size_t k = 0; k < c; ++k)
      if (arr.values[c * a + k] != other->values[c * b + k]) return false;
  }
  return true;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) return differ("usage: compare_frames <serial.vtp> <distributed.pvtp>");
  try {
    const VtpContents s = read_vtp(argv[1]), d = read_pvtp(argv[2]);
    const VtpArray* ids = d.find("id");
    if (!ids || s.count != d.count) return differ("no ids, or another number of particles");
    for (const VtpArray& arr : s.arrays)
      if (!d.find(arr.name) || d.find(arr.name)->components != arr.components) return differ("arrays");
    std::vector<int> seen(s.count, 0);
    for (std::size_t b = 0; b < d.count; ++b) {
      const auto id = static_cast<std::size_t>(ids->values[b]);
      if (id >= s.count || seen[id]++) return differ("an id missing or twice");
      if (!equal_points(s, d, id, b)) {
        std::printf("frames differ at particle %zu\n", id);
        return 1;
      }
    }
    std::printf("frames equal: %zu particles, %zu arrays\n", s.count, s.arrays.size());
    return 0;
  } catch (const std::exception& e) {
    return differ(e.what());
  }
}
