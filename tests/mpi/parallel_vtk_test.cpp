// Parallel VTK output: every rank's piece holds its particles with their global ids; the .pvtp
// read through ParaView's reader (vtkXMLPPolyDataReader) holds every particle exactly once, with
// its values bit for bit; the .pvd lists the .pvtp of every frame.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <fstream>
#include <sstream>

#include "mpi_env.hpp"
#include "sphark/io/pvtp_series.hpp"
#include "sphark/io/vtp_reader.hpp"

namespace sphark {
namespace {

using testing::world;

// One directory for all ranks (named after rank 0's pid), removed at the end.
std::filesystem::path shared_dir() {
  const std::int64_t pid = world().allreduce(std::int64_t(world().rank() == 0 ? ::getpid() : 0), ReduceOp::Max);
  const auto dir = std::filesystem::temp_directory_path() / ("sphark_pvtp_" + std::to_string(pid));
  if (world().rank() == 0) std::filesystem::create_directories(dir);
  world().barrier();
  return dir;
}

Real value(std::int64_t id, int k) { return 0.1 * double(id) + 0.01 * k + 1.0 / 3.0; }

TEST(ParallelVtk, EveryParticleOnceWithItsValues) {
  const auto dir = shared_dir();
  // Rank r holds ids r, r + P, ... (the last rank none when P > 1: an empty piece).
  const std::int64_t total = 101;
  const bool empty = world().size() > 1 && world().rank() == world().size() - 1;
  std::vector<std::int64_t> ids;
  for (std::int64_t id = world().rank(); id < total && !empty; id += world().size() - (world().size() > 1 ? 1 : 0))
    ids.push_back(id);
  std::vector<Real> pos, rho, vel;
  for (auto id : ids) {
    pos.insert(pos.end(), {value(id, 0), value(id, 1)});
    rho.push_back(value(id, 2));
    vel.insert(vel.end(), {value(id, 3), value(id, 4)});
  }
  ParticleFrame f{2, ids.size(), pos.data(), {{"density", rho.data(), 1}, {"velocity", vel.data(), 2}}, ids.data()};
  ParallelVtkSeriesWriter writer(world(), dir, "drop");
  writer.write(f, 0.0);
  const auto pvtp = writer.write(f, 0.5);
  world().barrier();
  std::size_t bad = 0;
  if (world().rank() == 0) {
    const VtpContents c = read_pvtp(pvtp);
    const VtpArray* id = c.find("id");
    const VtpArray* density = c.find("density");
    const VtpArray* velocity = c.find("velocity");
    EXPECT_TRUE(id && density && velocity);  // (no ASSERT: the other ranks wait below)
    EXPECT_EQ(c.count, std::size_t(total));
    std::vector<std::int64_t> seen;
    for (std::size_t i = 0; id && density && velocity && i < c.count; ++i) {
      const auto k = static_cast<std::int64_t>(id->values[i]);
      seen.push_back(k);
      bad += std::bit_cast<std::uint64_t>(c.points[3 * i]) != std::bit_cast<std::uint64_t>(value(k, 0));
      bad += density->values[i] != value(k, 2) || velocity->values[3 * i + 1] != value(k, 4);
    }
    std::sort(seen.begin(), seen.end());
    std::vector<std::int64_t> expected(total);
    for (std::int64_t k = 0; k < total; ++k) expected[k] = k;
    EXPECT_EQ(seen, expected);
    std::ifstream pvd(writer.pvd_path());
    std::stringstream text;
    text << pvd.rdbuf();
    EXPECT_NE(text.str().find("timestep=\"0.5\" group=\"\" part=\"0\" file=\"drop_00001.pvtp\""), std::string::npos);
    EXPECT_NE(text.str().find("drop_00000.pvtp"), std::string::npos);
  }
  // Each rank's own piece: its particles, in its order.
  const VtpContents mine = read_vtp(dir / ("drop_00001_" + std::to_string(world().rank()) + ".vtp"));
  EXPECT_EQ(mine.count, ids.size());
  const VtpArray* own = mine.find("id");
  for (std::size_t i = 0; own && i < ids.size(); ++i) bad += static_cast<std::int64_t>(own->values[i]) != ids[i];
  EXPECT_EQ(testing::global_sum(std::int64_t(bad)), 0);
  world().barrier();
  if (world().rank() == 0) std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace sphark
