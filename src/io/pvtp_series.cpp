#include "sphark/io/pvtp_series.hpp"

#include <cstdio>
#include <stdexcept>

#include "sphark/io/csv_writer.hpp"  // write_file_atomically
#include "sphark/io/vtk_series.hpp"  // write_vtp, pvd_collection_xml, xml_escape

namespace sphark {

std::string pvtp_xml(const ParticleFrame& frame, const std::vector<std::string>& pieces) {
  // As write_vtp writes them: Float64, scalars 1 component, vectors padded to 3; ids Int64.
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PPolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      "  <PPolyData GhostLevel=\"0\">\n"
      "    <PPointData>\n";
  for (const PointArray& a : frame.arrays)
    xml += "      <PDataArray type=\"Float64\" Name=\"" + xml_escape(a.name) + "\" NumberOfComponents=\"" +
           std::to_string(a.components == 1 ? 1 : 3) + "\"/>\n";
  if (frame.ids) xml += "      <PDataArray type=\"Int64\" Name=\"id\" NumberOfComponents=\"1\"/>\n";
  xml +=
      "    </PPointData>\n"
      "    <PPoints>\n"
      "      <PDataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"/>\n"
      "    </PPoints>\n";
  for (const std::string& piece : pieces) xml += "    <Piece Source=\"" + xml_escape(piece) + "\"/>\n";
  xml += "  </PPolyData>\n</VTKFile>\n";
  return xml;
}

ParallelVtkSeriesWriter::ParallelVtkSeriesWriter(Communicator comm, std::filesystem::path dir, std::string basename)
    : comm_(std::move(comm)), dir_(std::move(dir)), basename_(std::move(basename)) {
  if (basename_.empty() || basename_.find('/') != std::string::npos || basename_ == "." || basename_ == "..")
    throw std::invalid_argument("ParallelVtkSeriesWriter: bad basename '" + basename_ + "'");
}

std::filesystem::path ParallelVtkSeriesWriter::write(const ParticleFrame& frame, Real t) {
  char stem[64];
  std::snprintf(stem, sizeof stem, "_%05zu", frames_.size());
  const std::string frame_name = basename_ + stem;
  auto piece = [&](int rank) { return frame_name + "_" + std::to_string(rank) + ".vtp"; };
  ParticleFrame local = frame;
  std::int64_t no_id = 0;
  if (!local.ids) local.ids = &no_id;  // an empty piece still declares its "id" array
  comm_.collectively([&] {
    if (frame.count > 0 && !frame.ids) throw std::invalid_argument("ParallelVtkSeriesWriter: frame without ids");
    write_vtp(dir_ / piece(comm_.rank()), local, t);
  });
  const std::string pvtp = frame_name + ".pvtp";
  std::vector<std::pair<Real, std::string>> frames = frames_;
  frames.emplace_back(t, pvtp);
  comm_.collectively([&] {  // the index files only once every piece is in place
    if (comm_.rank() != 0) return;
    std::vector<std::string> pieces;
    for (int r = 0; r < comm_.size(); ++r) pieces.push_back(piece(r));
    write_file_atomically(dir_ / pvtp, pvtp_xml(local, pieces));
    write_file_atomically(pvd_path(), pvd_collection_xml(frames));
  });
  frames_ = std::move(frames);
  return dir_ / pvtp;
}

void ParallelVtkSeriesWriter::restore(std::vector<std::pair<Real, std::string>> frames) {
  comm_.collectively([&] {
    if (comm_.rank() == 0) write_file_atomically(pvd_path(), pvd_collection_xml(frames));
  });
  frames_ = std::move(frames);
}

}  // namespace sphark
