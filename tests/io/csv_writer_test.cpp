// CSV: header once, every value reads back bit-exactly (%.17g), flushed per row, width checked;
// write_file_atomically replaces whole files and never leaves a temporary behind.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "sphark/io/csv_writer.hpp"
#include "../support/temp_dir.hpp"

namespace sphark {
namespace {

std::vector<std::string> lines_of(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

std::vector<Real> split_reals(const std::string& line) {
  std::vector<Real> v;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) {
    char* end = nullptr;
    v.push_back(std::strtod(cell.c_str(), &end));
    EXPECT_EQ(*end, '\0') << cell;
  }
  return v;
}

TEST(CsvWriter, RoundTripsEveryBit) {
  test::TempDir dir;
  const auto path = dir.path() / "series.csv";
  std::mt19937_64 gen(3);
  std::uniform_real_distribution<Real> mant(-1, 1);
  std::uniform_int_distribution<int> expo(-320, 300);
  std::vector<std::vector<Real>> rows;
  rows.push_back({0.1, 1.0 / 3, -0.0, std::numeric_limits<Real>::denorm_min()});
  rows.push_back({std::numeric_limits<Real>::max(), std::numeric_limits<Real>::min(),
                  std::nextafter(1.0, 2.0), -std::numeric_limits<Real>::epsilon()});
  for (int r = 0; r < 200; ++r) {
    rows.push_back({std::ldexp(mant(gen), expo(gen)), std::ldexp(mant(gen), expo(gen)),
                    std::ldexp(mant(gen), expo(gen)), std::ldexp(mant(gen), expo(gen))});
  }
  {
    CsvWriter w(path, {"t", "mean_abs_div_v", "energy", "psi_max"});
    for (std::size_t r = 0; r < rows.size(); ++r) {
      w.row(rows[r]);
      // Flushed per row: the file already holds the header and r + 1 rows.
      EXPECT_EQ(lines_of(path).size(), r + 2);
    }
  }
  const auto lines = lines_of(path);
  ASSERT_EQ(lines.size(), rows.size() + 1);
  EXPECT_EQ(lines[0], "t,mean_abs_div_v,energy,psi_max");
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto got = split_reals(lines[r + 1]);
    ASSERT_EQ(got.size(), 4u);
    for (int c = 0; c < 4; ++c) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(got[c]), std::bit_cast<std::uint64_t>(rows[r][c]))
          << "row " << r << " col " << c << ": " << lines[r + 1];
    }
  }
}

TEST(CsvWriter, ChecksRowWidthAndColumnNames) {
  test::TempDir dir;
  CsvWriter w(dir.path() / "a.csv", {"t", "x"});
  EXPECT_THROW(w.row({1.0}), std::invalid_argument);
  EXPECT_THROW(w.row({1.0, 2.0, 3.0}), std::invalid_argument);
  w.row({1.0, 2.0});
  EXPECT_EQ(lines_of(dir.path() / "a.csv"), (std::vector<std::string>{"t,x", "1,2"}));
  EXPECT_THROW(CsvWriter(dir.path() / "b.csv", {}), std::invalid_argument);
  EXPECT_THROW(CsvWriter(dir.path() / "b.csv", {"a,b"}), std::invalid_argument);
  EXPECT_THROW(CsvWriter(dir.path() / "no_dir" / "c.csv", {"t"}), std::runtime_error);
}

TEST(CsvWriter, MovesKeepTheOpenFile) {
  test::TempDir dir;
  std::vector<CsvWriter> writers;
  writers.emplace_back(dir.path() / "a.csv", std::vector<std::string>{"t"});
  writers.emplace_back(dir.path() / "b.csv", std::vector<std::string>{"t"});  // moves a
  writers[0].row({1.5});
  CsvWriter c = std::move(writers[1]);
  c.row({2.5});
  EXPECT_THROW(writers[1].row({0.0}), std::logic_error);
  EXPECT_EQ(lines_of(dir.path() / "a.csv"), (std::vector<std::string>{"t", "1.5"}));
  EXPECT_EQ(lines_of(dir.path() / "b.csv"), (std::vector<std::string>{"t", "2.5"}));
}

TEST(WriteFileAtomically, ReplacesWholeFileWithoutTemporaries) {
  test::TempDir dir;
  const auto path = dir.path() / "summary.txt";
  write_file_atomically(path, "first\n");
  write_file_atomically(path, std::string(100000, 'x'));
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), std::string(100000, 'x'));
  EXPECT_EQ(dir.entries(), (std::set<std::string>{"summary.txt"}));
}

TEST(WriteFileAtomically, FailureLeavesTargetAndNoTemporary) {
  test::TempDir dir;
  // The target is a non-empty directory: the rename must fail, the temporary must go.
  const auto target = dir.path() / "occupied";
  std::filesystem::create_directories(target / "inside");
  EXPECT_THROW(write_file_atomically(target, "data"), std::runtime_error);
  EXPECT_EQ(dir.entries(), (std::set<std::string>{"occupied"}));
  EXPECT_TRUE(std::filesystem::is_directory(target / "inside"));
  EXPECT_THROW(write_file_atomically(dir.path() / "no_dir" / "f", "data"), std::runtime_error);
}

}  // namespace
}  // namespace sphark
