// Fuzz of the checkpoint reader, the current version (species, system data), and of --restart (issue #21):
//  - every truncation and every byte flipped (three masks) of a gas + sink checkpoint: without
//    the checksum repaired every one is an error; with the checksum repaired (the structure
//    itself corrupt) each decodes or fails with std::runtime_error, never anything else (no
//    huge allocation, no crash);
//  - a real water_drop checkpoint with each of its numbers (time, last step, every scalar) set to
//    a hostile value and the checksum repaired, restarted: exit 0, 2 (nothing written) or 3,
//    within the time limit, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <limits>

#include "option_fuzz.hpp"
#include "sphark/run/checkpoint.hpp"
#include "../support/temp_dir.hpp"

using namespace sphark;
using namespace sphark::test;
namespace fs = std::filesystem;

namespace {

Checkpoint two_species() {
  StateLayout L(5);
  L.add(Field::Position, 2).add(Field::Velocity, 2).add(Field::Density, 1);
  L.add_species(Species::Sink, 2).add(Field::Position, 2).add(Field::Mass, 1);
  Checkpoint c;
  c.program = "water_drop";
  c.argv = {"--t-end", "0.1"};
  c.species = describe_layout(L);
  c.t = 0.25;
  c.last_dt = 1e-3;
  c.set_scalar("sample", 3);
  c.set_text("run", "cleaned");
  c.set_text("diagnostics.csv", "t,e\n0,1\n");
  for (std::size_t k = 0; k < L.size(); ++k) c.y.push_back(0.5 * static_cast<Real>(k));
  c.stepper_data = {1, 2, 3};
  c.system_data = {0.5, 0.25};
  return c;
}

std::uint64_t fnv1a(const std::string& b, std::size_t n) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(b[i])) * 1099511628211ull;
  return h;
}

// The checksum (the last 8 bytes) recomputed over the rest.
std::string with_checksum(std::string b) {
  const std::size_t end = b.size() - 8;
  const std::uint64_t h = fnv1a(b, end);
  std::memcpy(b.data() + end, &h, 8);
  return b;
}

// "ok", "error: <what>" (std::runtime_error) or "OTHER: <what>" (anything else: a defect).
std::string decode_outcome(const std::string& bytes) {
  try {
    decode_checkpoint(bytes);
    return "ok";
  } catch (const std::runtime_error& e) {
    return std::string("error: ") + e.what();
  } catch (const std::exception& e) {
    return std::string("OTHER: ") + e.what();
  }
}

}  // namespace

TEST(CheckpointFuzz, EveryTruncationAndFlippedByteOfACurrentFileIsCaught) {
  const std::string good = encode_checkpoint(two_species());
  ASSERT_EQ(decode_outcome(good), "ok");
  ASSERT_EQ(decode_checkpoint(good).species.size(), 2u);
  for (std::size_t len = 0; len < good.size(); ++len)
    EXPECT_EQ(decode_outcome(good.substr(0, len)).rfind("error: ", 0), 0u) << "truncated to " << len;
  int decoded = 0, rejected = 0;
  for (std::size_t k = 0; k < good.size() - 8; ++k)
    for (const unsigned char mask : {0x01, 0x80, 0xff}) {
      std::string bad = good;
      bad[k] = static_cast<char>(bad[k] ^ mask);
      EXPECT_EQ(decode_outcome(bad).rfind("error: ", 0), 0u) << "byte " << k;  // the checksum
      const std::string repaired = k >= 16 ? with_checksum(bad) : bad;         // (header bytes: their own errors)
      const std::string what = decode_outcome(repaired);
      EXPECT_NE(what.rfind("OTHER", 0), 0u) << "byte " << k << " ^ " << int(mask) << ": " << what;
      (what == "ok" ? decoded : rejected) += 1;
    }
  std::printf("%zu bytes: every truncation and flip caught; with the checksum repaired %d decode (values changed), "
              "%d are errors\n", good.size(), decoded, rejected);
  EXPECT_GT(rejected, 0);
}

TEST(CheckpointFuzz, RestartFromACheckpointWithHostileNumbers) {
  const fs::path bin = require_example("water_drop");
  TempDir dir;
  const std::vector<std::string> tiny = {"--spacing", "0.25", "--cleaning", "on", "--no-render", "--threads", "1"};
  std::vector<std::string> first = tiny;
  for (const char* a : {"--t-end", "2e-4", "--checkpoint-every", "1e-4", "--out"}) first.push_back(a);
  first.push_back((dir.path() / "first").string());
  ASSERT_EQ(run(bin, first, dir.path()).exit_code, 0);
  const Checkpoint good = load_checkpoint(dir.path() / "first" / "cleaned" / "checkpoint.bin");
  // every number of the checkpoint, set to each hostile value
  std::vector<FuzzCase> cases;
  const Real nan = std::numeric_limits<Real>::quiet_NaN(), inf = std::numeric_limits<Real>::infinity();
  const std::vector<std::pair<std::string, Real>> values = {{"nan", nan}, {"inf", inf}, {"-1", -1}, {"0", 0}, {"1e300", 1e300}};
  std::vector<std::string> names = {"t", "last_dt"};
  for (const auto& [k, v] : good.scalars) names.push_back(k);
  int n = 0;
  for (const std::string& name : names)
    for (const auto& [text, v] : values) {
      Checkpoint c = good;
      if (name == "t") c.t = v;
      else if (name == "last_dt") c.last_dt = v;
      else c.set_scalar(name, v);
      const fs::path file = dir.path() / ("mutated_" + std::to_string(n++) + ".bin");
      save_checkpoint(file, c);
      cases.push_back({"water_drop", {"--t-end", "4e-4"}, {"--restart", file.string()}, true});
      cases.back().typed.push_back(name + "=" + text);  // (for the report only: removed below)
    }
  for (FuzzCase& c : cases) c.typed.pop_back();
  const std::vector<FuzzOutcome> all = run_all(cases, dir.path() / "cases");
  std::map<int, int> by_exit;
  for (std::size_t k = 0; k < all.size(); ++k) {
    const FuzzOutcome& o = all[k];
    const std::string number = names[k / values.size()] + " = " + values[k % values.size()].first;
    ++by_exit[o.r.f.exit_code];
    EXPECT_TRUE(o.verdict.empty()) << number << ": " << o.verdict << "\n" << o.r.f.err;
    EXPECT_FALSE(o.r.stopped) << number << ": no answer within the limit";
    if (o.r.f.exit_code != 0) std::printf("%-28s -> exit %d: %s\n", number.c_str(), o.r.f.exit_code, o.what.c_str());
  }
  std::printf("%zu restarts from mutated checkpoints:", all.size());
  for (const auto& [code, count] : by_exit) std::printf("  exit %d: %d", code, count);
  std::printf("\n");
}
