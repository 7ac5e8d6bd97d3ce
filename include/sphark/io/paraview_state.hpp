#pragma once
// A ready-made ParaView view of a run's frame series: view.pvsm in the output folder, opened
// with `paraview --state=view.pvsm` (ParaView 5.10 / 5.11 state format). Each view shows a
// .pvd series (io/vtk_series.hpp) with its particles drawn as discs ("Point Gaussian", radius
// half the mean spacing) coloured by one point array (vectors by magnitude), with a colour
// legend, the camera on the particles' bounds (2D: looking down z, parallel projection) and the
// animation on the series' time steps, opened on the last frame. Two or more views stand side
// by side; views colouring by the same array share one colour map, whose range holds the
// central 99 % of the values of every frame of every series that uses it (symmetric about zero
// for signed data, e.g. div B; the outliers saturate).
//
// Paths in the state are relative to the state file's folder, so the folder can be moved or
// copied; ParaView resolves them against its working directory, so open it from that folder
// (`cd out/water_drop && paraview --state=view.pvsm`) or let ParaView search the data files
// under the state's folder ("Load State" dialog: "Search files under specified directory").
//
//   write_paraview_state(out / "view.pvsm", {{"cleaned/drop.pvd", "pressure"},
//                                              {"control/drop.pvd", "pressure"}});
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark {

enum class ArrayAssociation { points, cells };

struct ParaViewView {
  std::filesystem::path series;  // the .pvd, relative to the state file's folder
  std::string array;             // the array to colour by
  ArrayAssociation association = ArrayAssociation::points;  // (the series carry point data)
};

// Writes `state_file` atomically. Reads every frame of every series (io/vtp_reader.hpp) for
// the colour ranges and the camera; std::runtime_error naming the file if a series or frame
// is missing or unreadable, a series has no frames, or a frame lacks the view's array;
// std::invalid_argument for no views, an absolute series path or cell association (no
// sphark series has cell data).
void write_paraview_state(const std::filesystem::path& state_file, const std::vector<ParaViewView>& views);

// write_paraview_state() for the end of a run: a failure is one warning line on stderr
// ("sphark: warning: <file>: <reason>") and false, never an exception (a finished run stands).
bool write_paraview_state_or_warn(const std::filesystem::path& state_file, const std::vector<ParaViewView>& views);

// The (time, file) entries of a .pvd collection, file names as written (relative to the .pvd).
std::vector<std::pair<Real, std::string>> read_pvd(const std::filesystem::path& pvd);

// What a state file names, for checking it against the output folder.
struct ParaViewStateRefs {
  std::vector<std::string> files;  // FileName of every reader, as written
  struct Colouring {
    std::string array;
    std::string association;       // ColorArrayName's field association: "points" or "cells"
    std::string reader_file;       // the FileName of the reader the representation shows
    double lo = 0, hi = 0;         // the colour map's range (first and last RGBPoints)
  };
  std::vector<Colouring> colourings;  // one per representation that colours by an array
  int views = 0;                      // RenderView proxies
  int layout_views = 0;               // views placed in the layout
};
// Parses a .pvsm (VTK's XML parser); std::runtime_error if it is not well-formed or not a
// ServerManagerState, or a representation names a missing reader or colour map.
ParaViewStateRefs read_paraview_state(const std::filesystem::path& state_file);

}  // namespace sphark
