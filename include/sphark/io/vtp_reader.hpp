#pragma once
// Reads a .vtp written by write_vtp / VtkSeriesWriter back into plain vectors (via
// vtkXMLPolyDataReader inside src/io). Used by the round-trip tests and by tools that need a
// written frame back without linking VTK themselves.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark {

struct VtpArray {
  std::string name;
  int components = 0;
  std::vector<Real> values;  // point-major, components per point
};

struct VtpContents {
  std::size_t count = 0;            // number of points
  std::size_t vertex_cells = 0;     // number of VTK_VERTEX cells
  std::vector<Real> points;         // 3 per point (padded with zeros as written)
  std::vector<VtpArray> arrays;     // point-data arrays in file order
  std::optional<Real> time;         // field-data "TimeValue", if present

  const VtpArray* find(const std::string& name) const;
};

// Throws std::runtime_error if the file is missing or not a readable .vtp.
VtpContents read_vtp(const std::filesystem::path& path);

// A .pvtp (parallel VTK, io/pvtp_series.hpp) through ParaView's reader (vtkXMLPPolyDataReader):
// all pieces merged, in piece order. Field data (the time) is not part of a .pvtp: time unset.
VtpContents read_pvtp(const std::filesystem::path& path);

// A frame of a series, serial or distributed: read_pvtp for a .pvtp, read_vtp otherwise.
VtpContents read_frame(const std::filesystem::path& path);

}  // namespace sphark
