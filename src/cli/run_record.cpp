#include "sphark/cli/run_record.hpp"

#include <omp.h>

#include <utility>

namespace sphark {

void record_options(RunRecord& record, const OptionParser& p) {
  Json given = Json::Array{}, types = Json::Object{};
  for (const OptionRecord& r : p.records()) {
    if (r.given) given.push_back(r.name);
    types[r.name] = r.type;
  }
  record.set("options_given", std::move(given));
  record.set("option_types", std::move(types));
  Json args = Json::Array{};
  for (const std::string& a : p.arguments()) args.push_back(a);
  record.set("arguments", std::move(args));
  if (!p.config_files().empty()) {
    Json files = Json::Array{};
    for (const auto& f : p.config_files()) files.push_back(f.string());
    record.set("config_files", std::move(files));
  }
}

RunRecord start_run_record(const OptionParser& p, Json options, const std::filesystem::path& dir, int ranks) {
  RunRecord record(dir, p.program(), std::move(options), omp_get_max_threads(), ranks);
  record_options(record, p);
  record.write();
  return record;
}

RunRecord start_run_record(const OptionParser& p, const std::filesystem::path& dir, int ranks) {
  return start_run_record(p, p.to_json(), dir, ranks);
}

}  // namespace sphark
