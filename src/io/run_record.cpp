#include "sphark/io/run_record.hpp"

#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <system_error>
#include <utility>

#include "sphark/io/atomic_file.hpp"
#include "sphark/io/build_info.hpp"

namespace sphark {

namespace fs = std::filesystem;

const char* outcome_name(RecordOutcome o) {
  switch (o) {
    case RecordOutcome::running: return "running";
    case RecordOutcome::ok: return "ok";
    case RecordOutcome::stopped: return "stopped";
    case RecordOutcome::failed: return "failed";
  }
  return "?";
}

std::string utc_timestamp() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char buf[40];
  const std::size_t n = std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &utc);
  std::snprintf(buf + n, sizeof buf - n, ".%03dZ", static_cast<int>(ms));
  return buf;
}

namespace {
std::string host_name() {
  char buf[256] = {};
  return ::gethostname(buf, sizeof buf - 1) == 0 ? std::string(buf) : "unknown";
}

std::string working_directory() {
  std::error_code ec;
  const fs::path p = fs::current_path(ec);
  return ec ? "unknown" : p.string();
}
}  // namespace

RunRecord::RunRecord(fs::path dir, std::string program, Json options, int threads, int ranks)
    : dir_(std::move(dir)), json_(Json::Object{}), started_(std::chrono::steady_clock::now()) {
  json_["program"] = std::move(program);
  json_["version"] = build_info_json();
  json_["options"] = std::move(options);
  json_["threads"] = threads;
  json_["ranks"] = ranks;
  json_["host"] = host_name();
  json_["working_directory"] = working_directory();
  json_["start"] = utc_timestamp();
  json_["outcome"] = outcome_name(RecordOutcome::running);
  write();
  start_mtime_ = fs::last_write_time(path());
}

RunRecord::RunRecord(RunRecord&& other) noexcept
    : dir_(std::move(other.dir_)), json_(std::move(other.json_)), started_(other.started_),
      start_mtime_(other.start_mtime_), finished_(std::exchange(other.finished_, true)) {}

RunRecord::~RunRecord() {
  if (!finished_) finish(RecordOutcome::failed, "ended without recording an outcome");
}

void RunRecord::set(const std::string& key, Json value) {
  Json::Object& o = json_.as_object();
  for (auto& [k, v] : o) {
    if (k == key) {
      v = std::move(value);
      return;
    }
  }
  const auto at = std::find_if(o.begin(), o.end(), [](const auto& kv) { return kv.first == "threads"; });
  o.emplace(at, key, std::move(value));
}

void RunRecord::write() {
  AtomicFile f(path());
  f << to_json_text(json_);
  f.commit();
}

std::vector<std::string> RunRecord::files_written() const {
  std::vector<std::string> files;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir_, fs::directory_options::skip_permission_denied, ec), end;
       !ec && it != end; it.increment(ec)) {
    std::error_code e;
    if (!it->is_regular_file(e) || e) continue;
    const std::string name = it->path().filename().string();
    if (name.size() > 1 && name[0] == '.' && name.find(".tmp.") != std::string::npos) continue;
    const auto t = it->last_write_time(e);
    if (!e && t >= start_mtime_) files.push_back(it->path().lexically_relative(dir_).string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

void RunRecord::finish(RecordOutcome outcome, const std::string& reason) {
  if (finished_) return;
  finished_ = true;
  try {
    json_["outcome"] = outcome_name(outcome);
    if (!reason.empty()) json_["reason"] = reason;
    json_["end"] = utc_timestamp();
    json_["wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
    Json::Array files;  // (run.json itself among them: written since the start)
    for (auto& f : files_written()) files.emplace_back(std::move(f));
    json_["files"] = std::move(files);
    write();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sphark: warning: cannot complete %s: %s\n", path().c_str(), e.what());
  }
}

int RunRecord::finish_with_exit_code(int code, const std::string& reason) {
  if (code == 0) {
    finish(RecordOutcome::ok, reason);
  } else if (code == 128 + SIGINT || code == 128 + SIGTERM) {
    finish(RecordOutcome::stopped, !reason.empty() ? reason : code == 128 + SIGINT ? "SIGINT" : "SIGTERM");
  } else {
    finish(RecordOutcome::failed, !reason.empty() ? reason : "exit code " + std::to_string(code));
  }
  return code;
}

Json read_run_record(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read '" + file.string() + "'");
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return parse_json(text.str());
  } catch (const JsonError& e) {
    throw std::runtime_error("'" + file.string() + "': " + e.what());
  }
}

}  // namespace sphark
