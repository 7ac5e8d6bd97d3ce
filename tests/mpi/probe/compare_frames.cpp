// compare_frames <a.vtp|a.pvtp> <b.vtp|b.pvtp>: the same particles with the same values, bit for
// bit. A serial frame (.vtp) holds particle a = global id a; a distributed frame (.pvtp) carries
// the ids of its pieces' points (Int64 "id", which is not compared as a value). Exit 0 and
// "frames equal: ..." if every point and every array of the first frame is found unchanged, for
// every id exactly once, in the second; exit 1 with the first difference.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphark/io/vtp_reader.hpp"

using namespace sphark;

namespace {
int differ(const std::string& what) {
  std::printf("frames differ: %s\n", what.c_str());
  return 1;
}

// The frame and, for each global id, the index of its point (every id once).
struct Frame {
  VtpContents contents;
  std::vector<std::size_t> point_of_id;
};

Frame indexed_frame(const std::string& path) {
  Frame f{read_frame(path), {}};
  const VtpArray* ids = f.contents.find("id");
  constexpr std::size_t none = static_cast<std::size_t>(-1);
  f.point_of_id.assign(f.contents.count, none);
  for (std::size_t p = 0; p < f.contents.count; ++p) {
    const auto id = ids ? static_cast<std::size_t>(ids->values[p]) : p;
    if (id >= f.contents.count || f.point_of_id[id] != none) throw std::runtime_error(path + ": an id missing or twice");
    f.point_of_id[id] = p;
  }
  return f;
}

// Every point and array value (but the ids) of point a of s equal to those of point b of d?
bool equal_points(const VtpContents& s, const VtpContents& d, std::size_t a, std::size_t b) {
  for (int k = 0; k < 3; ++k)
    if (s.points[3 * a + k] != d.points[3 * b + k]) return false;
  for (const VtpArray& arr : s.arrays) {
    if (arr.name == "id") continue;
    const VtpArray* other = d.find(arr.name);
    const std::size_t c = static_cast<std::size_t>(arr.components);
    for (std::size_t k = 0; k < c; ++k)
      if (arr.values[c * a + k] != other->values[c * b + k]) return false;
  }
  return true;
}

// After a difference: the largest relative difference of the points and of each array.
void print_differences(const Frame& s, const Frame& d) {
  auto relative = [](Real a, Real b) { return std::abs(a - b) / std::max<Real>(1e-300, std::max(std::abs(a), std::abs(b))); };
  Real points = 0;
  for (std::size_t id = 0; id < s.contents.count; ++id)
    for (int k = 0; k < 3; ++k)
      points = std::max(points, relative(s.contents.points[3 * s.point_of_id[id] + k], d.contents.points[3 * d.point_of_id[id] + k]));
  std::printf("  points: max relative difference %.3g\n", points);
  for (const VtpArray& arr : s.contents.arrays) {
    if (arr.name == "id") continue;
    const VtpArray* other = d.contents.find(arr.name);
    const std::size_t c = static_cast<std::size_t>(arr.components);
    Real worst = 0;
    for (std::size_t id = 0; id < s.contents.count; ++id)
      for (std::size_t k = 0; k < c; ++k)
        worst = std::max(worst, relative(arr.values[c * s.point_of_id[id] + k], other->values[c * d.point_of_id[id] + k]));
    std::printf("  %s: max relative difference %.3g\n", arr.name.c_str(), worst);
  }
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) return differ("usage: compare_frames <a.vtp|a.pvtp> <b.vtp|b.pvtp>");
  try {
    const Frame s = indexed_frame(argv[1]), d = indexed_frame(argv[2]);
    if (s.contents.count != d.contents.count) return differ("another number of particles");
    std::size_t compared = 0;
    for (const VtpArray& arr : s.contents.arrays) {
      if (arr.name == "id") continue;
      if (!d.contents.find(arr.name) || d.contents.find(arr.name)->components != arr.components) return differ("arrays");
      ++compared;
    }
    std::size_t first = s.contents.count, unequal = 0;
    for (std::size_t id = 0; id < s.contents.count; ++id)
      if (!equal_points(s.contents, d.contents, s.point_of_id[id], d.point_of_id[id])) {
        first = std::min(first, id);
        ++unequal;
      }
    if (unequal > 0) {
      std::printf("frames differ at particle %zu (%zu of %zu particles differ)\n", first, unequal, s.contents.count);
      print_differences(s, d);
      return 1;
    }
    std::printf("frames equal: %zu particles, %zu arrays\n", s.contents.count, compared);
    return 0;
  } catch (const std::exception& e) {
    return differ(e.what());
  }
}
