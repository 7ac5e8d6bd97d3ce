#include "sphark/run/run_outputs.hpp"

#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "sphark/io/csv_writer.hpp"
#include "sphark/io/vtk_series.hpp"

namespace sphark {

AtomicCsv::AtomicCsv(std::filesystem::path path, const std::vector<std::string>& columns)
    : path_(std::move(path)), columns_(columns.size()) {
  if (columns.empty()) throw std::invalid_argument("AtomicCsv: no columns for " + path_.string());
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i].empty() || columns[i].find_first_of(",\"\n\r") != std::string::npos)
      throw std::invalid_argument("AtomicCsv: bad column name '" + columns[i] + "' for " + path_.string());
    if (i) header_ += ',';
    header_ += columns[i];
  }
  header_ += '\n';
  text_ = header_;
}

void AtomicCsv::row(const std::vector<Real>& values) {
  if (values.size() != columns_)
    throw std::invalid_argument("AtomicCsv: " + std::to_string(values.size()) + " values for " +
                                std::to_string(columns_) + " columns in " + path_.string());
  char buf[32];
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.17g", values[i]);
    if (i) text_ += ',';
    text_ += buf;
  }
  text_ += '\n';
}

void AtomicCsv::flush() const { write_file_atomically(path_, text_); }

void AtomicCsv::restore(const std::string& text) {
  if (text.compare(0, header_.size(), header_) != 0)
    throw std::runtime_error("diagnostics in the checkpoint have other columns than " + path_.string());
  text_ = text;
}

ResumableVtkSeries::ResumableVtkSeries(std::filesystem::path dir, std::string basename)
    : dir_(std::move(dir)), basename_(std::move(basename)) {
  if (basename_.empty() || basename_.find('/') != std::string::npos)
    throw std::invalid_argument("ResumableVtkSeries: bad basename '" + basename_ + "'");
}

std::filesystem::path ResumableVtkSeries::write(const ParticleFrame& frame, Real t) {
  char name[64];
  std::snprintf(name, sizeof name, "_%05zu.vtp", frames_.size());
  const std::string file = basename_ + name;
  write_vtp(dir_ / file, frame, t);
  frames_.emplace_back(t, file);
  write_file_atomically(pvd_path(), pvd_collection_xml(frames_));
  return dir_ / file;
}

std::string ResumableVtkSeries::text() const { return frame_list_text(frames_); }

void ResumableVtkSeries::restore(const std::string& text, const std::filesystem::path& earlier_dir) {
  frames_ = parse_frame_list(text, dir_, earlier_dir);
  write_file_atomically(pvd_path(), pvd_collection_xml(frames_));
}

}  // namespace sphark
