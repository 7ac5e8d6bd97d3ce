#pragma once
// Summary table and pictures of the water-drop runs.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "drop_run.hpp"

namespace sphark {

using DropResults = std::vector<std::pair<std::string, DropRunSummary>>;

// <out>/summary.csv (one row per run) and, with a cleaned and a control run, their ratios.
void write_drop_summary(const std::filesystem::path& out, const DropResults& results);

// Charts (paper Figs. 8-10 and the semi-axes against the exact ellipse) and rendered frames.
// Frames were written every frame_every up to t_end.
void make_drop_pictures(const std::filesystem::path& out, const DropResults& results, Real frame_every, Real t_end);

}  // namespace sphark
