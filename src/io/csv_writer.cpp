#include "sphark/io/csv_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace sphark {

std::filesystem::path temporary_sibling(const std::filesystem::path& path) {
  std::string name = ".";  // (appended stepwise: "." + std::string trips GCC 12 -Wrestrict)
  name += path.filename().string();
  name += ".tmp.";
  name += std::to_string(::getpid());
  return path.parent_path() / name;
}

namespace {

[[noreturn]] void fail_commit(const std::filesystem::path& tmp, const std::string& what) {
  std::error_code ignored;
  std::filesystem::remove(tmp, ignored);
  throw std::runtime_error(what);
}

// fsync of a file or directory by name; 0 or an errno value.
int sync_path(const std::filesystem::path& p, int flags) {
  const int fd = ::open(p.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return errno;
  const int rc = ::fsync(fd) == 0 ? 0 : errno;
  ::close(fd);
  return rc == EINVAL || rc == EROFS ? 0 : rc;  // (file systems without fsync on directories)
}

}  // namespace

void commit_temporary(const std::filesystem::path& tmp, const std::filesystem::path& path) {
  if (const int e = sync_path(tmp, O_RDONLY))
    fail_commit(tmp, "cannot write '" + path.string() + "': fsync: " + std::strerror(e));
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) fail_commit(tmp, "cannot rename onto '" + path.string() + "': " + ec.message());
  const std::filesystem::path dir = path.parent_path().empty() ? "." : path.parent_path();
  if (const int e = sync_path(dir, O_RDONLY | O_DIRECTORY))
    throw std::runtime_error("cannot sync the directory of '" + path.string() + "': " + std::strerror(e));
}

void write_file_atomically(const std::filesystem::path& path, const std::string& contents) {
  const std::filesystem::path tmp = temporary_sibling(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("cannot write '" + path.string() + "': " + std::strerror(errno));
  std::size_t done = 0;
  while (done < contents.size()) {
    const ssize_t n = ::write(fd, contents.data() + done, contents.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int e = n < 0 ? errno : EIO;
      ::close(fd);
      fail_commit(tmp, "cannot write '" + path.string() + "': " + std::strerror(e));
    }
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) fail_commit(tmp, "cannot write '" + path.string() + "': " + std::strerror(errno));
  commit_temporary(tmp, path);
}

CsvWriter::CsvWriter(const std::filesystem::path& path, std::vector<std::string> columns)
    : path_(path), columns_(std::move(columns)) {
  if (columns_.empty()) throw std::invalid_argument("CsvWriter: no columns for " + path.string());
  for (const auto& c : columns_) {
    if (c.empty() || c.find_first_of(",\"\n\r") != std::string::npos) {
      throw std::invalid_argument("CsvWriter: bad column name '" + c + "' for " + path.string());
    }
  }
  file_ = std::fopen(path_.c_str(), "w");
  if (!file_) {
    throw std::runtime_error("cannot write '" + path_.string() + "': " + std::strerror(errno));
  }
  std::string header;
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (i) header += ',';
    header += columns_[i];
  }
  header += '\n';
  if (std::fputs(header.c_str(), file_) == EOF || std::fflush(file_) != 0) {
    const int e = errno;
    std::fclose(file_);
    file_ = nullptr;
    throw std::runtime_error("cannot write '" + path_.string() + "': " + std::strerror(e));
  }
}

CsvWriter::~CsvWriter() {
  if (file_) std::fclose(file_);
}

CsvWriter::CsvWriter(CsvWriter&& other) noexcept
    : path_(std::move(other.path_)), columns_(std::move(other.columns_)),
      file_(std::exchange(other.file_, nullptr)) {}

CsvWriter& CsvWriter::operator=(CsvWriter&& other) noexcept {
  if (this != &other) {
    if (file_) std::fclose(file_);
    path_ = std::move(other.path_);
    columns_ = std::move(other.columns_);
    file_ = std::exchange(other.file_, nullptr);
  }
  return *this;
}

void CsvWriter::row(const std::vector<Real>& values) {
  if (!file_) throw std::logic_error("CsvWriter: row() on a moved-from writer");
  if (values.size() != columns_.size()) {
    throw std::invalid_argument("CsvWriter: row of " + std::to_string(values.size()) +
                                " values for " + std::to_string(columns_.size()) +
                                " columns in " + path_.string());
  }
  std::string line;
  char buf[40];
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) line += ',';
    std::snprintf(buf, sizeof buf, "%.17g", values[i]);
    line += buf;
  }
  line += '\n';
  if (std::fputs(line.c_str(), file_) == EOF || std::fflush(file_) != 0) {
    throw std::runtime_error("cannot write '" + path_.string() + "': " + std::strerror(errno));
  }
}

}  // namespace sphark
