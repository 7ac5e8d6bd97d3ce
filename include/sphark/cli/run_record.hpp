#pragma once
// The run record of a program driven by an OptionParser (io/run_record.hpp): written into the
// output folder after the options are checked and the folder exists, before computing starts.
//
//   start_run(core, p.program());                        // threads set, folder created
//   RunRecord record = start_run_record(p, core.out);    // run.json: options, version, start
//   ... the run; write_paraview_state(...) ...
//   return record.finish_with_exit_code(code, reason);   // end, outcome, files
#include <filesystem>

#include "sphark/cli/options.hpp"
#include "sphark/io/run_record.hpp"

namespace sphark {

// A RunRecord of p.program() in `dir` with every option (p.to_json()) and, before "threads":
// "options_given" (the names given on the command line or in a config), "option_types"
// ({name: "real" | "integer" | ...}), "arguments" (p.arguments(): what was parsed; on a restart
// the checkpoint's stored options, then the ones given) and, if any, "config_files". threads = omp_get_max_threads() (set by --threads / start_run).
RunRecord start_run_record(const OptionParser& p, const std::filesystem::path& dir, int ranks = 1);
// The same with the option values `options` (p.to_json() taken before the values were changed,
// e.g. times converted from the scene's unit: the record keeps what was given, so that
// `--config run.json` runs it again).
RunRecord start_run_record(const OptionParser& p, Json options, const std::filesystem::path& dir, int ranks = 1);

// The same entries for a record made elsewhere (a study's or ensemble's run: its own options).
void record_options(RunRecord& record, const OptionParser& p);

}  // namespace sphark
