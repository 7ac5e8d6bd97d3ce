#pragma once
// A time series of particle frames for ParaView / VTK:
//   <dir>/<basename>_00000.vtp, _00001.vtp, ...  vtkPolyData, one vertex cell per particle,
//       appended raw binary, zlib compressed, Float64 throughout (positions and arrays are
//       written bit-exactly); 1D/2D positions padded with zeros, 2-component vectors padded to
//       3; the time is stored as the field-data array "TimeValue".
//   <dir>/<basename>.pvd  the collection (file + timestep of every frame), rewritten after each
//       frame.
// Every file is written to a temporary name in <dir> and renamed into place, so a killed run
// leaves only complete files. VTK itself stays inside src/io (no VTK type in this header).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/io/particle_frame.hpp"

namespace sphark {

class VtkSeriesWriter {
 public:
  // `dir` must exist (see prepare_output_dir). `basename` must be a plain file-name stem
  // (no '/'); throws std::invalid_argument otherwise.
  VtkSeriesWriter(std::filesystem::path dir, std::string basename);

  // Writes frame number frames().size() at time t and rewrites the .pvd. Returns the .vtp path.
  // Throws std::invalid_argument for a malformed frame (dim not 1..3, components not 1..3,
  // null data with count > 0), std::runtime_error if a file cannot be written.
  std::filesystem::path write(const ParticleFrame& frame, Real t);

  std::filesystem::path pvd_path() const { return dir_ / (basename_ + ".pvd"); }
  // (time, file name relative to dir) of every frame written so far.
  const std::vector<std::pair<Real, std::string>>& frames() const { return frames_; }

 private:
  std::filesystem::path dir_;
  std::string basename_;
  std::vector<std::pair<Real, std::string>> frames_;
};

// Writes one frame to `path` as a .vtp (same format as the series; atomically).
void write_vtp(const std::filesystem::path& path, const ParticleFrame& frame, Real t);

// s with & < > " ' as XML entities (file and array names in .pvd / .pvtp files).
std::string xml_escape(const std::string& s);

// The .pvd text for the given (time, file) entries (file names XML-escaped, times as %.17g).
std::string pvd_collection_xml(const std::vector<std::pair<Real, std::string>>& frames);

// A series' frame list as a checkpoint keeps it: "t file" per line (t as %.17g), and its parse
// (std::runtime_error for a malformed line). `dir`, `earlier_dir` (may be empty): a listed file
// found in earlier_dir (the run that wrote the list) and not in dir (a restart into another
// --out) is listed by its path relative to dir, so that the new .pvd finds every frame.
std::string frame_list_text(const std::vector<std::pair<Real, std::string>>& frames);
std::vector<std::pair<Real, std::string>> parse_frame_list(const std::string& text, const std::filesystem::path& dir,
                                                           const std::filesystem::path& earlier_dir = {});

}  // namespace sphark
