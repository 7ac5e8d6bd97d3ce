#pragma once
// examples/second_derivative_1d: shared declarations of the reproduction of seed 001, Tables 1-5
// and Figures 2, 4, 5 (see README.md).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sphark/derivatives1d/study1d.hpp"

namespace scene {

using sphark::Index;
using sphark::Real;

struct Options {
  std::filesystem::path out = "out/second_derivative_1d";
  std::uint64_t seed = 1;
  int seeds = 1;    // random tables repeated over seeds seed, seed+1, ..., seed+seeds-1
  int levels = 8;   // N = 11, 21, ..., 10 * 2^(levels-1) + 1
  bool plots = true;
  bool timing = true;
  bool profile = false;  // --profile: wall-time split (output vs the rest)
};

// Tables: CSV `method,N,e_N,p_N` and Markdown on stdout.
void write_table_csv(const std::filesystem::path& file, const std::vector<sphark::d1::TableRow>& rows);
void print_table_markdown(const std::string& title, const std::vector<sphark::d1::TableRow>& rows);

// --seeds K: mean and spread of e_N over K random sets; CSV and Markdown.
void seed_statistics(int table, const Options& opt, const std::vector<Index>& sizes);

// Figures 2, 4 (c = 2, 3), 5 as CSV columns x, exact, CSPM, BIM, ICSPM.
void write_figure_data(const Options& opt);

// Time to assemble / apply / solve each operator vs N, with its error: timing.csv.
void write_timing(const Options& opt, const std::vector<Index>& sizes);

}  // namespace scene
