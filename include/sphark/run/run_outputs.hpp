#pragma once
// Output files of a run that survive a kill and a restart:
//  - AtomicCsv: a CSV time series kept in memory and written whole, atomically (temporary file +
//    rename), whenever flush() is called (run loops flush at every VTK frame, checkpoint, failure
//    and at the end). A killed run leaves the file as of the last flush: complete rows only.
//    (io/CsvWriter appends and flushes row by row; a kill can leave a partial last row.)
//  - ResumableVtkSeries: <dir>/<basename>_NNNNN.vtp + <basename>.pvd, every file atomic (as
//    io/VtkSeriesWriter), whose list of frames can be saved to / restored from a checkpoint.
// Both give their contents as text for a checkpoint (times and values as %.17g: bit-exact).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/io/particle_frame.hpp"

namespace sphark {

class AtomicCsv {
 public:
  // Throws std::invalid_argument for no columns or a name with ',', '"' or a newline.
  AtomicCsv(std::filesystem::path path, const std::vector<std::string>& columns);
  // One row of %.17g values; std::invalid_argument on a wrong value count.
  void row(const std::vector<Real>& values);
  // Writes the whole file atomically (std::runtime_error on failure).
  void flush() const;
  const std::string& text() const { return text_; }
  // Replaces the contents (header included) with `text` from a checkpoint; the header must be
  // this writer's header (std::runtime_error otherwise).
  void restore(const std::string& text);
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::string header_, text_;
  std::size_t columns_ = 0;
};

class ResumableVtkSeries {
 public:
  // `dir` must exist; `basename` a plain stem (std::invalid_argument otherwise).
  ResumableVtkSeries(std::filesystem::path dir, std::string basename);
  // Writes frame number frames().size() and rewrites the .pvd. Returns the .vtp path.
  std::filesystem::path write(const ParticleFrame& frame, Real t);
  const std::vector<std::pair<Real, std::string>>& frames() const { return frames_; }
  std::filesystem::path pvd_path() const { return dir_ / (basename_ + ".pvd"); }
  // "t file" per line; restore() parses it (std::runtime_error for a malformed text) and
  // rewrites the .pvd, so frames after the restart continue the numbering. `earlier_dir`: where
  // the listed frames were written (a restart into another --out): each listed file found there
  // and not here is then listed by its path relative to this directory, so that the new .pvd
  // (and ParaView) finds every frame of the run.
  std::string text() const;
  void restore(const std::string& text, const std::filesystem::path& earlier_dir = {});

 private:
  std::filesystem::path dir_;
  std::string basename_;
  std::vector<std::pair<Real, std::string>> frames_;
};

}  // namespace sphark
