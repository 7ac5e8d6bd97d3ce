// Checkpoint files: bit-exact round trip, atomic write, and one clear error for every kind of
// bad file (missing, not a checkpoint, other version, truncated, corrupt, other layout).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "sphark/io/csv_writer.hpp"
#include "sphark/run/checkpoint.hpp"
#include "../support/temp_dir.hpp"

using namespace sphark;
using sphark::test::TempDir;

namespace {
StateLayout layout3() {
  StateLayout L(3);
  L.add(Field::Position, 2).add(Field::Velocity, 2).add(Field::Density, 1);
  return L;
}

Checkpoint sample() {
  const StateLayout L = layout3();
  Checkpoint c;
  c.program = "water_drop";
  c.argv = {"--t-end", "0.1", "--out", "dir with space"};
  c.species = describe_layout(L);
  c.t = 0.1 + 1e-17;
  c.last_dt = 3.0e-7 / 7.0;
  c.set_scalar("sample", 42);
  c.set_scalar("tiny", std::numeric_limits<Real>::denorm_min());
  c.set_text("run", "cleaned");
  c.set_text("csv", std::string("t,x\n1,2\n") + '\0' + "binary");
  for (std::size_t k = 0; k < L.size(); ++k) c.y.push_back(std::sqrt(2.0) * static_cast<Real>(k) - 1.0 / 3.0);
  c.y[1] = -0.0;
  c.y[2] = std::numeric_limits<Real>::max();
  c.stepper_data = {1.0 / 3.0, std::numeric_limits<Real>::quiet_NaN()};
  c.system_data = {0.125, 1.0 / 7.0, -0.0};
  return c;
}

std::string what_of_load(const std::filesystem::path& p) {
  try {
    load_checkpoint(p);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(loaded)";
}

void put(const std::filesystem::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }
}  // namespace

TEST(Checkpoint, RoundTripIsBitExact) {
  TempDir dir;
  const Checkpoint c = sample();
  save_checkpoint(dir.path() / "c.bin", c);
  EXPECT_EQ(dir.entries(), std::set<std::string>{"c.bin"});  // no temporary left behind
  const Checkpoint r = load_checkpoint(dir.path() / "c.bin");
  EXPECT_EQ(r.program, c.program);
  EXPECT_EQ(r.argv, c.argv);
  EXPECT_EQ(r.species, c.species);
  EXPECT_EQ(r.texts, c.texts);
  ASSERT_EQ(r.y.size(), c.y.size());
  ASSERT_EQ(r.stepper_data.size(), c.stepper_data.size());
  const auto same_bits = [](Real a, Real b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  EXPECT_TRUE(same_bits(r.t, c.t));
  EXPECT_TRUE(same_bits(r.last_dt, c.last_dt));
  EXPECT_TRUE(same_bits(r.scalar("tiny"), c.scalar("tiny")));
  EXPECT_EQ(r.scalar("sample"), 42);
  for (std::size_t k = 0; k < c.y.size(); ++k) EXPECT_TRUE(same_bits(r.y[k], c.y[k])) << k;
  for (std::size_t k = 0; k < c.stepper_data.size(); ++k) EXPECT_TRUE(same_bits(r.stepper_data[k], c.stepper_data[k]));
  ASSERT_EQ(r.system_data.size(), c.system_data.size());
  for (std::size_t k = 0; k < c.system_data.size(); ++k) EXPECT_TRUE(same_bits(r.system_data[k], c.system_data[k]));
  EXPECT_FALSE(layout_mismatch(r, layout3()).has_value());
}

TEST(Checkpoint, MissingNamesAreErrors) {
  const Checkpoint c = sample();
  EXPECT_THROW(c.scalar("nope"), std::runtime_error);
  EXPECT_THROW(c.text("nope"), std::runtime_error);
}

TEST(Checkpoint, BadFilesGiveOneClearError) {
  TempDir dir;
  const std::string good = encode_checkpoint(sample());
  const auto p = dir.path() / "x.bin";
  EXPECT_NE(what_of_load(dir.path() / "absent.bin").find("no such file"), std::string::npos);
  put(p, "t,x\n1,2\n");
  EXPECT_NE(what_of_load(p).find("not a sphark checkpoint"), std::string::npos);
  put(p, "");
  EXPECT_NE(what_of_load(p).find("not a sphark checkpoint"), std::string::npos);
  std::string other = good;
  other[8] = 99;  // version field
  put(p, other);
  EXPECT_NE(what_of_load(p).find("unsupported checkpoint version 99"), std::string::npos);
  // every truncation is detected (a killed writer cannot produce one, a copy can)
  for (std::size_t len : {std::size_t{12}, std::size_t{20}, good.size() / 2, good.size() - 1}) {
    put(p, good.substr(0, len));
    EXPECT_NE(what_of_load(p), "(loaded)") << len;
  }
  // every single flipped byte after the header is detected by the checksum
  for (std::size_t k = 16; k < good.size(); k += 7) {
    std::string bad = good;
    bad[k] = static_cast<char>(bad[k] ^ 0x5a);
    put(p, bad);
    EXPECT_NE(what_of_load(p).find(p.string()), std::string::npos) << k;
    EXPECT_NE(what_of_load(p), "(loaded)") << k;
  }
}

TEST(Checkpoint, LayoutMismatchIsNamed) {
  const Checkpoint c = sample();
  StateLayout more(4);
  more.add(Field::Position, 2).add(Field::Velocity, 2).add(Field::Density, 1);
  const auto why = layout_mismatch(c, more);
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("3 gas particles"), std::string::npos) << *why;
  EXPECT_NE(why->find("4 gas particles"), std::string::npos) << *why;
  StateLayout psi(3);
  psi.add(Field::Position, 2).add(Field::Velocity, 2).add(Field::Density, 1).add(Field::Psi, 1);
  EXPECT_TRUE(layout_mismatch(c, psi).has_value());
}

TEST(Checkpoint, AtomicWriteKeepsThePreviousFileWhenTheDirectoryIsGone) {
  TempDir dir;
  EXPECT_THROW(save_checkpoint(dir.path() / "missing" / "c.bin", sample()), std::runtime_error);
  EXPECT_TRUE(dir.entries().empty());
}

TEST(Checkpoint, EverySpeciesRoundTrips) {
  TempDir dir;
  Checkpoint c = sample();
  StateLayout L = layout3();
  L.add_species(Species::Sink, 2).add(Field::Position, 2).add(Field::Mass, 1);
  c.species = describe_layout(L);
  c.y.resize(L.size(), 0.25);
  save_checkpoint(dir.path() / "c.bin", c);
  const Checkpoint r = load_checkpoint(dir.path() / "c.bin");
  ASSERT_EQ(r.species.size(), 2u);
  EXPECT_EQ(r.species[1].name, "sink");
  EXPECT_EQ(r.species[1].particles, 2u);
  EXPECT_EQ(r.species, c.species);
  EXPECT_FALSE(layout_mismatch(r, L).has_value());
  const auto why = layout_mismatch(r, L.with_count(Species::Sink, 3));
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("2 sink particles"), std::string::npos) << *why;
}

// A version-1 file (one species, written before species existed) still loads, as the gas.
TEST(Checkpoint, VersionOneReadsAsOneGasSpecies) {
  std::string b = "SPHARKCK";
  const auto pod = [&b](auto v) { b.append(reinterpret_cast<const char*>(&v), sizeof v); };
  const auto str = [&](const std::string& s) { pod(std::uint64_t{s.size()}), b += s; };
  pod(std::uint32_t{1}), pod(std::uint32_t{0x01020304u});
  str("water_drop"), pod(std::uint64_t{0});
  pod(std::uint64_t{3}), pod(std::uint64_t{1}), str("position"), pod(std::uint32_t{2});  // 3 particles, x only
  pod(0.5), pod(1e-3), pod(std::uint64_t{0}), pod(std::uint64_t{0});
  pod(std::uint64_t{6});
  for (int k = 0; k < 6; ++k) pod(static_cast<double>(k));
  pod(std::uint64_t{0});
  std::uint64_t h = 1469598103934665603ull;
  for (char ch : b) h = (h ^ static_cast<unsigned char>(ch)) * 1099511628211ull;
  pod(h);
  const Checkpoint c = decode_checkpoint(b);
  ASSERT_EQ(c.species.size(), 1u);
  EXPECT_EQ(c.species[0].name, "gas");
  EXPECT_EQ(c.particles(), 3u);
  StateLayout L(3);
  L.add(Field::Position, 2);
  EXPECT_FALSE(layout_mismatch(c, L).has_value());
  EXPECT_EQ(c.y[5], 5.0);
}

// A version-2 file (before the system's resume data) still loads, with no system data: the file
// of version 3 without its last count, under version number 2.
TEST(Checkpoint, VersionTwoReadsWithoutSystemData) {
  Checkpoint c = sample();
  c.system_data.clear();
  std::string b = encode_checkpoint(c);
  b.erase(b.size() - 16, 8);  // the system data's count (0), just before the checksum
  const auto with_version = [&b](std::uint32_t version) {  // and the checksum recomputed
    std::memcpy(b.data() + 8, &version, sizeof version);
    std::uint64_t h = 1469598103934665603ull;
    for (std::size_t i = 0; i + 8 < b.size(); ++i) h = (h ^ static_cast<unsigned char>(b[i])) * 1099511628211ull;
    std::memcpy(b.data() + b.size() - 8, &h, sizeof h);
    return b;
  };
  const Checkpoint r = decode_checkpoint(with_version(2));
  EXPECT_TRUE(r.system_data.empty());
  EXPECT_EQ(r.stepper_data.size(), c.stepper_data.size());
  EXPECT_EQ(r.y.size(), c.y.size());
  EXPECT_EQ(r.texts, c.texts);
  // the same bytes as version 3 are one count short: rejected, not misread
  EXPECT_THROW(decode_checkpoint(with_version(3)), std::runtime_error);
}
