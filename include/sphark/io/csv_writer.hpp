#pragma once
// Plain CSV time series (one header line, then one row of numbers per call, each written with
// %.17g so it reads back bit-exactly) and an atomic whole-file writer.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark {

// Writes `contents` to `path` so that `path` is either absent/unchanged or complete: the bytes
// go to a temporary file in the same directory, which is fsync()ed and then rename()d onto
// `path`; then the directory is fsync()ed, so the new file also survives a crash of the machine.
// Throws std::runtime_error (naming the path and the reason) on failure and removes the
// temporary file.
void write_file_atomically(const std::filesystem::path& path, const std::string& contents);

// The last two steps of an atomic write for files written by other code (VTK, scripts): fsync
// `tmp`, rename it onto `path`, fsync the directory. std::runtime_error on failure (the
// temporary file is removed).
void commit_temporary(const std::filesystem::path& tmp, const std::filesystem::path& path);

// Temporary name used by the atomic writers: ".<name>.tmp.<pid>" in the same directory.
std::filesystem::path temporary_sibling(const std::filesystem::path& path);

class CsvWriter {
 public:
  // Creates/truncates `path` and writes the header `columns` joined by ','.
  // Throws std::invalid_argument for no columns or a column name containing ',', '"' or a
  // newline; std::runtime_error if the file cannot be opened.
  CsvWriter(const std::filesystem::path& path, std::vector<std::string> columns);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  CsvWriter(CsvWriter&& other) noexcept;
  CsvWriter& operator=(CsvWriter&& other) noexcept;

  // One row, each value as %.17g, then flushed. Throws std::invalid_argument if
  // values.size() != columns().size(), std::runtime_error on a write error.
  void row(const std::vector<Real>& values);

  const std::vector<std::string>& columns() const { return columns_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::vector<std::string> columns_;
  std::FILE* file_ = nullptr;
};

}  // namespace sphark
