#include "sphark/io/visualise.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

extern char** environ;

namespace sphark {
namespace {

constexpr const char* kPython = "/usr/bin/python3";

bool warn(const std::string& script, const std::string& why) {
  std::fprintf(stderr, "sphark: warning: vis/%s: %s; no picture made\n", script.c_str(),
               why.c_str());
  return false;
}

// First executable `name` on $PATH, or empty.
std::string on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string candidate = dirs.substr(start, end - start) + "/" + name;
    if (end > start && ::access(candidate.c_str(), X_OK) == 0) return candidate;
    start = end + 1;
  }
  return {};
}

}  // namespace

std::filesystem::path vis_dir() { return std::filesystem::path(SPHARK_SOURCE_DIR) / "vis"; }

bool run_python(const std::string& script, const std::vector<std::string>& args,
                bool needs_display) {
  const std::filesystem::path script_path = vis_dir() / script;
  if (!std::filesystem::is_regular_file(script_path)) {
    return warn(script, "script not found at " + script_path.string());
  }
  if (::access(kPython, X_OK) != 0) return warn(script, std::string(kPython) + " not found");

  std::vector<std::string> argv_s;
  const char* display = std::getenv("DISPLAY");
  if (needs_display && (!display || !*display)) {
    const std::string xvfb = on_path("xvfb-run");
    if (xvfb.empty()) return warn(script, "no $DISPLAY and xvfb-run not found");
    argv_s = {xvfb, "-a"};
  }
  argv_s.push_back(kPython);
  argv_s.push_back(script_path.string());
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);

  std::fflush(stdout);
  std::fflush(stderr);
  pid_t pid = 0;
  const int rc = ::posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ);
  if (rc != 0) return warn(script, std::string("cannot start ") + argv[0] + ": " + std::strerror(rc));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return warn(script, std::string("waitpid: ") + std::strerror(errno));
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return true;
  if (WIFEXITED(status)) {
    return warn(script, "exited with status " + std::to_string(WEXITSTATUS(status)));
  }
  return warn(script, "killed by signal " + std::to_string(WIFSIGNALED(status) ? WTERMSIG(status) : 0));
}

}  // namespace sphark
