// frame_from_state: views the state in place, names arrays after the fields, and a frame made
// from a state round-trips through write_vtp/read_vtp bit-exactly.
#include <gtest/gtest.h>

#include "sphark/io/state_frame.hpp"
#include "sphark/io/vtk_series.hpp"
#include "sphark/io/vtp_reader.hpp"
#include "../support/temp_dir.hpp"

namespace sphark {
namespace {

TEST(StateFrame, ViewsEveryFieldInPlace) {
  const std::size_t n = 37;
  StateLayout L(n);
  L.add(Field::Position, 2).add(Field::Velocity, 2).add(Field::Density, 1).add(Field::Psi, 1);
  std::vector<Real> y(L.size());
  for (std::size_t k = 0; k < y.size(); ++k) y[k] = 0.1 * static_cast<Real>(k) - 3.0;

  const ParticleFrame f = frame_from_state(L, y.data());
  EXPECT_EQ(f.dim, 2);
  EXPECT_EQ(f.count, n);
  EXPECT_EQ(f.positions, y.data() + L.offset(Field::Position));
  ASSERT_EQ(f.arrays.size(), 3u);
  EXPECT_EQ(f.arrays[0].name, "velocity");
  EXPECT_EQ(f.arrays[0].data, y.data() + L.offset(Field::Velocity));
  EXPECT_EQ(f.arrays[0].components, 2);
  EXPECT_EQ(f.arrays[1].name, "density");
  EXPECT_EQ(f.arrays[2].name, "psi");

  test::TempDir dir;
  write_vtp(dir.path() / "s.vtp", f, 0.0);
  const VtpContents r = read_vtp(dir.path() / "s.vtp");
  // Particle i's velocity is (y[v + 2i], y[v + 2i + 1]), written padded as (vx, vy, 0).
  const auto v = L.offset(Field::Velocity);
  const auto& vel = r.find("velocity")->values;
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(vel[3 * i], y[v + 2 * i]);
    EXPECT_EQ(vel[3 * i + 1], y[v + 2 * i + 1]);
    EXPECT_EQ(vel[3 * i + 2], 0.0);
    EXPECT_EQ(r.points[3 * i], y[2 * i]);
    EXPECT_EQ(r.find("psi")->values[i], y[L.offset(Field::Psi) + i]);
  }
}

TEST(StateFrame, RejectsLayoutsAFrameCannotShow) {
  std::vector<Real> y(100);
  StateLayout no_pos(5);
  no_pos.add(Field::Density, 1);
  EXPECT_THROW(frame_from_state(no_pos, y.data()), std::invalid_argument);
  StateLayout wide(5);
  wide.add(Field::Position, 2).add(Field::MagneticField, 4);
  EXPECT_THROW(frame_from_state(wide, y.data()), std::invalid_argument);
}

}  // namespace
}  // namespace sphark
