#pragma once
// A text output file built in memory (it is an std::ostringstream) and written atomically by
// commit(): temporary file + fsync + rename (write_file_atomically), so a killed run leaves the
// file either absent / as before or complete. The commit counts as Output in the --profile
// summary (core/profile.hpp).
//
//   AtomicFile out(dir / "table1.csv");
//   out << "method,N,e_N\n" << ...;
//   out.commit();  // std::runtime_error naming the path on failure
#include <filesystem>
#include <sstream>
#include <utility>

#include "sphark/core/profile.hpp"
#include "sphark/io/csv_writer.hpp"

namespace sphark {

class AtomicFile : public std::ostringstream {
 public:
  explicit AtomicFile(std::filesystem::path path) : path_(std::move(path)) {}
  void commit() {
    ScopedPhase phase(Phase::Output);
    write_file_atomically(path_, str());
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace sphark
