#pragma once
// Parallel VTK output of a distributed run, which ParaView opens as one data set per time:
//   <dir>/<basename>_00000_<rank>.vtp   each rank's particles (write_vtp: same format as the
//                                        serial series), with the global ids as Int64 "id";
//   <dir>/<basename>_00000.pvtp          PPolyData: the point arrays (names, types,
//                                        components) and the pieces, written by rank 0;
//   <dir>/<basename>.pvd                 the series of .pvtp files with their times, rank 0.
// Every file is written atomically (temporary name, rename). write() is collective: the
// .pvtp and .pvd are written only once every piece is complete, and a failure on any rank
// throws CollectiveError on every rank (the previous frames stay valid).
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/io/particle_frame.hpp"
#include "sphark/parallel/communicator.hpp"

namespace sphark {

class ParallelVtkSeriesWriter {
 public:
  // `dir` must exist on every rank (a shared file system); basename as for VtkSeriesWriter.
  ParallelVtkSeriesWriter(Communicator comm, std::filesystem::path dir, std::string basename);

  // Collective: this rank's particles (frame.ids required: the global ids) at time t; every
  // rank passes the same array names and components. Returns the .pvtp path.
  std::filesystem::path write(const ParticleFrame& frame, Real t);

  std::filesystem::path pvd_path() const { return dir_ / (basename_ + ".pvd"); }
  const std::vector<std::pair<Real, std::string>>& frames() const { return frames_; }
  // Collective: a restart continues the series of `frames` (parse_frame_list); rank 0 rewrites
  // the .pvd, so frames after the restart continue the numbering.
  void restore(std::vector<std::pair<Real, std::string>> frames);

 private:
  Communicator comm_;
  std::filesystem::path dir_;
  std::string basename_;
  std::vector<std::pair<Real, std::string>> frames_;
};

// The .pvtp text for pieces (file names relative to the .pvtp) of frames shaped like `frame`.
std::string pvtp_xml(const ParticleFrame& frame, const std::vector<std::string>& pieces);

}  // namespace sphark
