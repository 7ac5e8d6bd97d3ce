#include "sphark/io/visualise.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <random>
#include <thread>

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

ProcessResult run_process(const std::vector<std::string>& argv_in, double timeout_seconds) {
  if (argv_in.empty()) return {false, "empty command"};
  std::vector<std::string> args = argv_in;
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawnattr_t attr;
  ::posix_spawnattr_init(&attr);
  ::posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);  // own group: xvfb-run + children
  ::posix_spawnattr_setpgroup(&attr, 0);
  std::fflush(stdout);
  std::fflush(stderr);
  pid_t pid = 0;
  const int rc = ::posix_spawn(&pid, argv[0], nullptr, &attr, argv.data(), environ);
  ::posix_spawnattr_destroy(&attr);
  if (rc != 0) return {false, "cannot start " + args[0] + ": " + std::strerror(rc)};

  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto waited = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  int status = 0;
  bool timed_out = false;
  double term_sent_at = -1;
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) return {false, std::string("waitpid: ") + std::strerror(errno)};
    if (!timed_out && waited() > timeout_seconds) {
      timed_out = true;
      term_sent_at = waited();
      ::kill(-pid, SIGTERM);
    } else if (timed_out && waited() > term_sent_at + 2) {
      ::kill(-pid, SIGKILL);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(timed_out ? 20 : 10));
  }
  if (timed_out) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "still running after %g s, killed", timeout_seconds);
    return {false, buf};
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return {true, ""};
  if (WIFEXITED(status)) return {false, "exited with status " + std::to_string(WEXITSTATUS(status))};
  return {false, "killed by signal " + std::to_string(WIFSIGNALED(status) ? WTERMSIG(status) : 0)};
}

namespace {
// The X display number from which `xvfb-run -a` looks for a free one: drawn at random from 60,000
// for every call. With one start for all (xvfb-run's 99), a call right after another reused the
// display whose server was still shutting down, and that server removed the new one's socket on
// its way out ("bad X server connection"); with numbers from the process id (pid mod 400) two
// test processes 400 ids apart met the same way in a fresh-clone CI run (session 27). A random
// start makes reusing a display of the last seconds unlikely for any pair of callers.
std::string first_display_to_try() {
  static std::mutex mutex;
  static std::mt19937 draw(std::random_device{}() ^ static_cast<unsigned>(::getpid()));
  std::lock_guard<std::mutex> lock(mutex);
  return std::to_string(100 + std::uniform_int_distribution<unsigned>(0, 59999)(draw));
}
}  // namespace

bool run_python(const std::string& script, const std::vector<std::string>& args,
                bool needs_display, double timeout_seconds) {
  const std::filesystem::path script_path = vis_dir() / script;
  if (!std::filesystem::is_regular_file(script_path)) {
    return warn(script, "script not found at " + script_path.string());
  }
  if (::access(kPython, X_OK) != 0) return warn(script, std::string(kPython) + " not found");

  std::vector<std::string> argv;
  const char* display = std::getenv("DISPLAY");
  if (needs_display && (!display || !*display)) {
    const std::string xvfb = on_path("xvfb-run");
    if (xvfb.empty()) return warn(script, "no $DISPLAY and xvfb-run not found");
    argv = {xvfb, "-n", first_display_to_try(), "-a"};  // -n first: -a starts its search from it
  }
  argv.push_back(kPython);
  argv.push_back(script_path.string());
  argv.insert(argv.end(), args.begin(), args.end());
  const ProcessResult r = run_process(argv, timeout_seconds);
  return r.ok || warn(script, r.error);
}

bool run_python_batch(const std::vector<PythonJob>& jobs, bool needs_display, double timeout_seconds, int processes) {
  if (jobs.empty()) return true;
  std::vector<std::string> args;
  if (processes > 0) args = {"--processes", std::to_string(processes)};
  for (const PythonJob& job : jobs) {
    if (&job != &jobs.front()) args.emplace_back(":::");  // vis/batch.py's job separator
    args.push_back(job.script);
    args.insert(args.end(), job.args.begin(), job.args.end());
  }
  return run_python("batch.py", args, needs_display, timeout_seconds);
}

}  // namespace sphark
