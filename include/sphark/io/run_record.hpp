#pragma once
// The record of one run, <dir>/run.json: what ran, how it was built, every option's value and
// how it ended, so that every output folder says how it was made and can be re-run from it
// (`program --config <dir>/run.json`: the "options" object, see cli/options.hpp).
//
//   RunRecord record(out, "water_drop", parser.to_json(), threads);  // writes run.json now
//   record.set("variant", "cleaned");                                 // optional extra entries
//   ... the run ...
//   return record.finish_with_exit_code(code, reason);                // end, outcome, files
//
// run.json (written atomically at the start and at the end; keys in this order):
//   program, version {version, git_commit, git_modified, build_type, sanitizers, compiler,
//   sundials, vtk}, options {name: value} (every option, defaults included), the entries of
//   set() (e.g. options_given, arguments), threads, ranks, host, working_directory,
//   start (UTC, ISO 8601), outcome ("running" until the end, then "ok", "stopped" or "failed"),
//   reason (why it stopped or failed), end, wall_seconds, files (every file below <dir> written
//   since the start, relative paths, sorted; run.json included).
// A record never finished (the program left main without finish()) is finished by the
// destructor as failed, "ended without recording an outcome"; one killed outright keeps
// "running".
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "sphark/io/json.hpp"

namespace sphark {

enum class RecordOutcome { running, ok, stopped, failed };
const char* outcome_name(RecordOutcome o);  // "running", "ok", "stopped", "failed"

// The current UTC time as ISO 8601 with milliseconds, "2024-05-01T12:34:56.789Z".
std::string utc_timestamp();

class RunRecord {
 public:
  // Writes <dir>/run.json (dir must exist); std::runtime_error if it cannot be written.
  // `options`: a JSON object of option values (OptionParser::to_json()); threads: the OpenMP
  // threads the run uses; ranks: MPI ranks (1 without MPI).
  RunRecord(std::filesystem::path dir, std::string program, Json options, int threads, int ranks = 1);
  RunRecord(RunRecord&& other) noexcept;  // `other` is left finished (its destructor writes nothing)
  RunRecord& operator=(RunRecord&&) = delete;
  ~RunRecord();

  // An extra entry (before "threads"), written with the next write(); replaces one of that name.
  void set(const std::string& key, Json value);
  // Rewrites run.json now (e.g. after set()).
  void write();
  // Ends the record: end time, wall time, outcome and reason, files; writes it. The first call
  // counts; later ones are ignored. Never throws (a failed write is one line on stderr).
  void finish(RecordOutcome outcome, const std::string& reason = "");
  // finish() from a program's exit code: 0 ok; 128 + SIGINT / SIGTERM stopped (reason "SIGINT"
  // / "SIGTERM" unless given); anything else failed (reason, or "exit code N"). Returns code.
  int finish_with_exit_code(int code, const std::string& reason = "");

  // Regular files below the record's folder modified since the record was started (relative,
  // sorted; the atomic writers' temporaries ".<name>.tmp.<pid>" left out).
  std::vector<std::string> files_written() const;
  const Json& json() const { return json_; }
  std::filesystem::path path() const { return dir_ / "run.json"; }
  bool finished() const { return finished_; }

 private:
  std::filesystem::path dir_;
  Json json_;
  std::chrono::steady_clock::time_point started_;
  std::filesystem::file_time_type start_mtime_;  // of run.json's first write: the files' clock
  bool finished_ = false;
};

// The JSON of a run.json (std::runtime_error naming the file if it cannot be read or parsed).
Json read_run_record(const std::filesystem::path& file);

}  // namespace sphark
