// VTK output: a written frame reads back (vtkXMLPolyDataReader, via read_vtp in src/io)
// bit-exactly, padded as documented; the .pvd lists every frame with its time; no temporaries.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <fstream>
#include <limits>
#include <random>
#include <regex>
#include <sstream>

#include "sphark/io/vtk_series.hpp"
#include "sphark/io/vtp_reader.hpp"
#include "../support/temp_dir.hpp"

namespace sphark {
namespace {

bool same_bits(Real a, Real b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// Values with full 53-bit mantissas over many decades, plus awkward ones.
std::vector<Real> random_values(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<Real> mant(-1, 1);
  std::uniform_int_distribution<int> expo(-300, 300);
  std::vector<Real> v(n);
  for (auto& x : v) x = std::ldexp(mant(gen), expo(gen));
  const Real special[] = {0.1, 1.0 / 3, -0.0, std::numeric_limits<Real>::denorm_min(),
                          std::numeric_limits<Real>::max(), std::numeric_limits<Real>::epsilon()};
  for (std::size_t k = 0; k < std::size(special) && k < n; ++k) v[k] = special[k];
  return v;
}

struct FrameData {
  int dim;
  std::size_t n;
  std::vector<Real> pos, rho, vel, b;
  ParticleFrame frame() const {
    ParticleFrame f;
    f.dim = dim;
    f.count = n;
    f.positions = pos.data();
    f.arrays = {{"density", rho.data(), 1}, {"velocity", vel.data(), dim}, {"B", b.data(), 3}};
    return f;
  }
};

FrameData make_frame(int dim, std::size_t n, std::uint64_t seed) {
  return {dim, n, random_values(dim * n, seed), random_values(n, seed + 1),
          random_values(dim * n, seed + 2), random_values(3 * n, seed + 3)};
}

// Every value of `c` (components per point, padded to `padded`) equals the source bit for bit;
// padding is exactly +0.
void expect_padded_equal(const std::vector<Real>& src, int c, const std::vector<Real>& got,
                         int padded, std::size_t n) {
  ASSERT_EQ(got.size(), n * padded);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < padded; ++k) {
      const Real expect = k < c ? src[i * c + k] : 0.0;
      ASSERT_TRUE(same_bits(got[i * padded + k], expect))
          << "point " << i << " component " << k << ": " << got[i * padded + k] << " vs " << expect;
    }
  }
}

class VtpRoundTrip : public ::testing::TestWithParam<int> {};

TEST_P(VtpRoundTrip, PositionsAndArraysBitExact) {
  const int dim = GetParam();
  test::TempDir dir;
  const std::size_t n = 777;
  const FrameData d = make_frame(dim, n, 42 + dim);
  const Real t = 0.1 + 1e-17 * 3;
  const auto path = dir.path() / "frame.vtp";
  write_vtp(path, d.frame(), t);

  const VtpContents r = read_vtp(path);
  EXPECT_EQ(r.count, n);
  EXPECT_EQ(r.vertex_cells, n);
  ASSERT_TRUE(r.time.has_value());
  EXPECT_TRUE(same_bits(*r.time, t));
  expect_padded_equal(d.pos, dim, r.points, 3, n);
  ASSERT_EQ(r.arrays.size(), 3u);
  ASSERT_NE(r.find("density"), nullptr);
  EXPECT_EQ(r.find("density")->components, 1);
  expect_padded_equal(d.rho, 1, r.find("density")->values, 1, n);
  ASSERT_NE(r.find("velocity"), nullptr);
  EXPECT_EQ(r.find("velocity")->components, dim == 1 ? 1 : 3);
  expect_padded_equal(d.vel, dim, r.find("velocity")->values, dim == 1 ? 1 : 3, n);
  ASSERT_NE(r.find("B"), nullptr);
  expect_padded_equal(d.b, 3, r.find("B")->values, 3, n);
  EXPECT_EQ(dir.entries(), (std::set<std::string>{"frame.vtp"}));
}

INSTANTIATE_TEST_SUITE_P(Dims, VtpRoundTrip, ::testing::Values(1, 2, 3));

TEST(VtpFormat, AppendedRawZlibFloat64) {
  test::TempDir dir;
  const FrameData d = make_frame(2, 50, 7);
  const auto path = dir.path() / "f.vtp";
  write_vtp(path, d.frame(), 0.5);
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), head.size());
  EXPECT_NE(head.find("type=\"PolyData\""), std::string::npos);
  EXPECT_NE(head.find("compressor=\"vtkZLibDataCompressor\""), std::string::npos);
  EXPECT_NE(head.find("header_type=\"UInt64\""), std::string::npos);
  EXPECT_NE(head.find("<AppendedData encoding=\"raw\">"), std::string::npos);
  EXPECT_EQ(head.find("format=\"ascii\""), std::string::npos);
  EXPECT_EQ(head.find("type=\"Float32\""), std::string::npos);
  EXPECT_NE(head.find("Name=\"density\" format=\"appended\""), std::string::npos);
}

TEST(VtkSeries, PvdListsEveryFrameWithItsTime) {
  test::TempDir dir;
  VtkSeriesWriter w(dir.path(), "drop");
  const std::vector<Real> times = {0.0, 1e-3, 0.1 / 3, 0.25};
  std::set<std::string> expected = {"drop.pvd"};
  for (std::size_t k = 0; k < times.size(); ++k) {
    const FrameData d = make_frame(2, 20 + k, 100 + k);
    const auto p = w.write(d.frame(), times[k]);
    char name[32];
    std::snprintf(name, sizeof name, "drop_%05zu.vtp", k);
    EXPECT_EQ(p, dir.path() / name);
    expected.insert(name);
    // Re-read the .pvd after every frame: it must already list frames 0..k.
    std::ifstream in(w.pvd_path());
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string pvd = ss.str();
    const std::regex ds(R"re(<DataSet timestep="([^"]+)" group="" part="0" file="([^"]+)"/>)re");
    std::size_t m = 0;
    for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), ds); it != std::sregex_iterator();
         ++it, ++m) {
      ASSERT_LE(m, k);
      EXPECT_TRUE(same_bits(std::strtod((*it)[1].str().c_str(), nullptr), times[m]));
      char want[32];
      std::snprintf(want, sizeof want, "drop_%05zu.vtp", m);
      EXPECT_EQ((*it)[2].str(), want);
      EXPECT_EQ(read_vtp(dir.path() / want).count, 20 + m);
    }
    EXPECT_EQ(m, k + 1);
    EXPECT_NE(pvd.find("<VTKFile type=\"Collection\""), std::string::npos);
    EXPECT_EQ(dir.entries(), expected);  // no temporaries left behind
  }
}

TEST(VtkSeries, RejectsBadInput) {
  test::TempDir dir;
  EXPECT_THROW(VtkSeriesWriter(dir.path(), "a/b"), std::invalid_argument);
  EXPECT_THROW(VtkSeriesWriter(dir.path(), ""), std::invalid_argument);
  FrameData d = make_frame(2, 5, 1);
  ParticleFrame f = d.frame();
  f.dim = 4;
  EXPECT_THROW(write_vtp(dir.path() / "x.vtp", f, 0), std::invalid_argument);
  f = d.frame();
  f.arrays[0].components = 4;
  EXPECT_THROW(write_vtp(dir.path() / "x.vtp", f, 0), std::invalid_argument);
  f = d.frame();
  f.positions = nullptr;
  EXPECT_THROW(write_vtp(dir.path() / "x.vtp", f, 0), std::invalid_argument);
  EXPECT_TRUE(dir.entries().empty());
  EXPECT_THROW(read_vtp(dir.path() / "missing.vtp"), std::runtime_error);
}

TEST(VtkSeries, UnwritableDirectoryThrowsAndLeavesNothing) {
  test::TempDir dir;
  VtkSeriesWriter w(dir.path() / "no_such_dir", "x");
  const FrameData d = make_frame(2, 5, 1);
  EXPECT_THROW(w.write(d.frame(), 0), std::runtime_error);
  EXPECT_TRUE(dir.entries().empty());
  EXPECT_TRUE(w.frames().empty());
}

}  // namespace
}  // namespace sphark
