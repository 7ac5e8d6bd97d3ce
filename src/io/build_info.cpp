#include "sphark/io/build_info.hpp"

#include <sundials/sundials_version.h>
#include <vtkVersion.h>

#include "sphark/build_info_generated.hpp"  // <build>/generated, written by cmake/build_info.cmake

namespace sphark {

namespace {
std::string compiler_text() {
#if defined(__clang__)
  return std::string("clang ") + __clang_version__;
#elif defined(__GNUC__)
  return std::string("gcc ") + __VERSION__;
#else
  return "unknown";
#endif
}

std::string sundials_text() {
  char buf[64] = {};
  return SUNDIALSGetVersion(buf, static_cast<int>(sizeof buf)) == 0 ? std::string(buf) : "unknown";
}
}  // namespace

const BuildInfo& build_info() {
  static const BuildInfo info{SPHARK_VERSION,
                              SPHARK_GIT_COMMIT,
                              SPHARK_GIT_MODIFIED,
                              SPHARK_BUILD_TYPE,
                              std::string(SPHARK_SANITIZE) == "ON" ? "address,undefined" : "none",
                              compiler_text(),
                              sundials_text(),
                              vtkVersion::GetVTKVersion()};
  return info;
}

Json build_info_json() {
  const BuildInfo& b = build_info();
  Json j = Json::Object{};
  j["version"] = b.version;
  j["git_commit"] = b.git_commit;
  j["git_modified"] = b.git_modified == "unknown" ? Json("unknown") : Json(b.git_modified == "yes");
  j["build_type"] = b.build_type;
  j["sanitizers"] = b.sanitizers;
  j["compiler"] = b.compiler;
  j["sundials"] = b.sundials;
  j["vtk"] = b.vtk;
  return j;
}

}  // namespace sphark
