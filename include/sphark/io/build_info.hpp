#pragma once
// What built this program, for run records (io/run_record.hpp): the project version, the git
// commit of the source tree and whether the tree differed from it ("yes" / "no"; both
// "unknown" outside a git checkout, e.g. a build from a tarball), the build type, the
// compiler, and the SUNDIALS and VTK versions of the libraries this program runs with.
// The git state and build type come from cmake/build_info.cmake (refreshed at every build).
#include <string>

#include "sphark/io/json.hpp"

namespace sphark {

struct BuildInfo {
  std::string version;       // the project's version (CMake project(VERSION))
  std::string git_commit;    // 40 hex digits or "unknown"
  std::string git_modified;  // "yes", "no" or "unknown"
  std::string build_type;    // CMAKE_BUILD_TYPE
  std::string sanitizers;    // "address,undefined" or "none"
  std::string compiler;      // "gcc 12.2.0", ...
  std::string sundials;      // SUNDIALSGetVersion()
  std::string vtk;           // vtkVersion::GetVTKVersion()
};

const BuildInfo& build_info();
// {"version", "git_commit", "git_modified" (true / false / "unknown"), "build_type", ...}
Json build_info_json();

}  // namespace sphark
