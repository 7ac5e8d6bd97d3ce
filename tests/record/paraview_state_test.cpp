// io/paraview_state.hpp: the state names only files and arrays that exist in the output (read
// back with VTK's XML parser and io/vtp_reader), by paths relative to its folder (so the folder
// can move), and colour ranges that cover every frame.
#include <gtest/gtest.h>

#include <cmath>

#include "sphark/io/paraview_state.hpp"
#include "sphark/io/vtk_series.hpp"
#include "sphark/io/vtp_reader.hpp"
#include "../support/temp_dir.hpp"

using namespace sphark;
namespace fs = std::filesystem;

namespace {
// A 2D series of `frames` frames of n particles with "pressure" (signed, growing in time) and
// "velocity" (2 components); 3D adds "column_density".
void write_series(const fs::path& dir, const std::string& name, int dim, int frames, int n = 50) {
  fs::create_directories(dir);
  VtkSeriesWriter w(dir, name);
  std::vector<Real> x(dim * n), p(n), v(2 * n), sigma(n);
  for (int k = 0; k < frames; ++k) {
    for (int i = 0; i < n; ++i) {
      for (int c = 0; c < dim; ++c) x[dim * i + c] = std::cos(i + c) * (1 + 0.1 * k);
      p[i] = (k + 1) * std::sin(0.3 * i);
      v[2 * i] = 3 * k, v[2 * i + 1] = 4 * k;  // |v| = 5k
      sigma[i] = 1 + i;
    }
    ParticleFrame f{dim, static_cast<std::size_t>(n), x.data(),
                    {{"pressure", p.data(), 1}, {"velocity", v.data(), 2}}};
    if (dim == 3) f.arrays.push_back({"column_density", sigma.data(), 1});
    w.write(f, 0.5 * k);
  }
}

// Every reader's file exists relative to the state's folder, every frame of it too, and each
// coloured array is a point array of every frame; its colour range lies within the values and
// holds 99 % of them (vectors: magnitudes; the outliers saturate).
void check_state_against_output(const fs::path& state) {
  const fs::path dir = state.parent_path();
  const ParaViewStateRefs refs = read_paraview_state(state);
  ASSERT_FALSE(refs.files.empty());
  for (const auto& f : refs.files) {
    EXPECT_FALSE(fs::path(f).is_absolute()) << f;
    ASSERT_TRUE(fs::is_regular_file(dir / f)) << f;
    for (const auto& [t, frame] : read_pvd(dir / f)) EXPECT_TRUE(fs::is_regular_file(dir / fs::path(f).parent_path() / frame));
  }
  ASSERT_FALSE(refs.colourings.empty());
  for (const auto& c : refs.colourings) {
    EXPECT_EQ(c.association, "points");
    ASSERT_TRUE(fs::is_regular_file(dir / c.reader_file)) << c.reader_file;
    std::size_t values = 0, outside = 0;
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& [t, frame] : read_pvd(dir / c.reader_file)) {
      const VtpContents v = read_vtp(dir / fs::path(c.reader_file).parent_path() / frame);
      const VtpArray* a = v.find(c.array);
      ASSERT_NE(a, nullptr) << frame << " has no " << c.array;
      for (std::size_t i = 0; i < v.count; ++i) {
        double sq = 0;
        for (int k = 0; k < a->components; ++k) sq += a->values[i * a->components + k] * a->values[i * a->components + k];
        const double value = a->components == 1 ? a->values[i] : std::sqrt(sq);
        ++values;
        outside += value < c.lo || value > c.hi;
        lo = std::min(lo, value), hi = std::max(hi, value);
      }
    }
    EXPECT_LT(c.lo, c.hi);
    EXPECT_LE(outside, values / 100 + 1) << c.array;
    if (lo < 0 && hi > 0) {  // signed: symmetric, within the largest |value|
      EXPECT_EQ(c.lo, -c.hi) << c.array;
      EXPECT_LE(c.hi, std::max(-lo, hi)) << c.array;
    } else {
      EXPECT_GE(c.lo, lo) << c.array;
      EXPECT_LE(c.hi, hi) << c.array;
    }
  }
  EXPECT_EQ(refs.layout_views, refs.views);
}
}  // namespace

TEST(ParaViewState, NamesOnlyFilesAndArraysThatExistAndMovesWithItsFolder) {
  test::TempDir dir;
  const fs::path out = dir.path() / "run";
  write_series(out / "cleaned", "drop", 2, 3);
  write_series(out / "control", "drop", 2, 3);
  write_paraview_state(out / "view.pvsm", {{"cleaned/drop.pvd", "pressure"}, {"control/drop.pvd", "velocity"}});
  check_state_against_output(out / "view.pvsm");
  const ParaViewStateRefs refs = read_paraview_state(out / "view.pvsm");
  EXPECT_EQ(refs.files, (std::vector<std::string>{"cleaned/drop.pvd", "control/drop.pvd"}));
  ASSERT_EQ(refs.colourings.size(), 2u);
  EXPECT_EQ(refs.views, 2);
  // pressure is signed: a symmetric range (checked above); |v| = 5k, k = 0, 1, 2, in equal shares
  EXPECT_EQ(refs.colourings[1].lo, 0);
  EXPECT_EQ(refs.colourings[1].hi, 10);
  // the folder moved elsewhere: the same state still resolves
  const fs::path moved = dir.path() / "elsewhere" / "copy";
  fs::create_directories(moved.parent_path());
  fs::rename(out, moved);
  check_state_against_output(moved / "view.pvsm");
}

TEST(ParaViewState, TwoArraysOfOneSeriesAndA3DSeries) {
  test::TempDir dir;
  write_series(dir.path(), "orszag_tang", 2, 2);
  write_paraview_state(dir.path() / "view.pvsm", {{"orszag_tang.pvd", "pressure"}, {"orszag_tang.pvd", "velocity"},
                                                  {"orszag_tang.pvd", "pressure"}});
  const ParaViewStateRefs refs = read_paraview_state(dir.path() / "view.pvsm");
  EXPECT_EQ(refs.files.size(), 1u);  // one reader for all views
  EXPECT_EQ(refs.views, 3);
  EXPECT_EQ(refs.layout_views, 3);  // every view placed, none twice
  check_state_against_output(dir.path() / "view.pvsm");
  test::TempDir dir3;
  write_series(dir3.path() / "collapse", "collapse", 3, 2);
  write_paraview_state(dir3.path() / "view.pvsm", {{"collapse/collapse.pvd", "column_density"}});
  check_state_against_output(dir3.path() / "view.pvsm");
}

TEST(ParaViewState, RefusesWhatItCannotShow) {
  test::TempDir dir;
  write_series(dir.path(), "drop", 2, 1);
  const fs::path state = dir.path() / "view.pvsm";
  try {
    write_paraview_state(state, {{"drop.pvd", "div_B"}});
    ADD_FAILURE() << "no error for a missing array";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("has no point array 'div_B'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(write_paraview_state(state, {{"missing.pvd", "pressure"}}), std::runtime_error);
  EXPECT_THROW(write_paraview_state(state, {{dir.path() / "drop.pvd", "pressure"}}), std::invalid_argument);
  EXPECT_THROW(write_paraview_state(state, {}), std::invalid_argument);
  EXPECT_FALSE(fs::exists(state));  // nothing written for a refused state
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(write_paraview_state_or_warn(state, {{"drop.pvd", "div_B"}}));
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(err.rfind("sphark: warning: " + state.string() + ": ", 0), 0u) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1);
}

TEST(ParaViewState, AFewOutliersSaturateInsteadOfWashingOutTheRest) {
  test::TempDir dir;
  const int n = 1000;
  std::vector<Real> x(2 * n), q(n);
  for (int i = 0; i < n; ++i) {
    x[2 * i] = i % 40, x[2 * i + 1] = i / 40;
    q[i] = i % 2 ? 1.0 + 1e-3 * i : -(1.0 + 1e-3 * i);  // |q| in [1, 2)
  }
  q[7] = 1e6;  // one particle blown up
  VtkSeriesWriter w(dir.path(), "s");
  w.write(ParticleFrame{2, static_cast<std::size_t>(n), x.data(), {{"div_B", q.data(), 1}}}, 0);
  write_paraview_state(dir.path() / "view.pvsm", {{"s.pvd", "div_B"}});
  const auto c = read_paraview_state(dir.path() / "view.pvsm").colourings.at(0);
  EXPECT_EQ(c.lo, -c.hi);
  EXPECT_GT(c.hi, 1.9);  // 99 % of |q| inside ...
  EXPECT_LT(c.hi, 2.0);  // ... and not stretched to 1e6
  check_state_against_output(dir.path() / "view.pvsm");
}
