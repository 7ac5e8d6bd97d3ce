#pragma once
// Runs a built example program (build/bin/<name>, found next to this test's own build folder)
// with stdout and stderr captured; optionally with extra environment variables, in a working
// directory of its own, and with a time limit (SIGTERM at the limit, SIGKILL one second later).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>
#include <utility>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "../support/file_bytes.hpp"

namespace sphark::test {

inline std::filesystem::path example_binary(const std::string& name) {
  return std::filesystem::read_symlink("/proc/self/exe").parent_path().parent_path() / "bin" / name;
}

// The example program `name`, which the build makes before this test program (tests/CMakeLists.txt):
// a missing one is a failure of the test, never a skip.
inline std::filesystem::path require_example(const std::string& name) {
  const std::filesystem::path bin = example_binary(name);
  if (!std::filesystem::exists(bin)) ADD_FAILURE() << bin << " not built";
  return bin;
}

struct Spawned {
  pid_t pid = -1;
  std::filesystem::path out, err;
};

using Environment = std::vector<std::pair<std::string, std::string>>;

// Starts `binary args...` with stdout/stderr redirected to files in `log_dir`, with `env` set on
// top of the test's own environment, in the working directory `cwd` (empty: the test's).
inline Spawned spawn(const std::filesystem::path& binary, const std::vector<std::string>& args,
                     const std::filesystem::path& log_dir, const Environment& env = {},
                     const std::filesystem::path& cwd = {}) {
  Spawned s{-1, log_dir / "stdout.txt", log_dir / "stderr.txt"};
  std::vector<std::string> all{binary.string()};
  all.insert(all.end(), args.begin(), args.end());
  const pid_t pid = fork();
  if (pid == 0) {
    const int o = open(s.out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = open(s.err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(o, 1);
    dup2(e, 2);
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    setenv("OMP_NUM_THREADS", "1", 1);
    for (const auto& [k, v] : env) setenv(k.c_str(), v.c_str(), 1);
    if (!cwd.empty() && chdir(cwd.c_str()) != 0) _exit(126);
    execv(argv[0], argv.data());
    _exit(127);
  }
  s.pid = pid;
  return s;
}

inline std::string slurp(const std::filesystem::path& p) { return file_bytes(p); }

// The files a .pvd lists, relative to its own folder, in its order.
inline std::vector<std::string> pvd_files(const std::filesystem::path& pvd) {
  const std::string xml = slurp(pvd);
  const std::regex file_re("file=\"([^\"]+)\"");
  std::vector<std::string> files;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), file_re); it != std::sregex_iterator(); ++it)
    files.push_back((*it)[1].str());
  return files;
}

struct Finished {
  int exit_code = -1;  // -1: killed by a signal
  std::string out, err;
};

inline Finished wait_for(const Spawned& s) {
  int status = 0;
  waitpid(s.pid, &status, 0);
  Finished f;
  f.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  f.out = slurp(s.out);
  f.err = slurp(s.err);
  return f;
}

inline Finished run(const std::filesystem::path& binary, const std::vector<std::string>& args,
                    const std::filesystem::path& log_dir, const Environment& env = {}) {
  return wait_for(spawn(binary, args, log_dir, env));
}

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// How a process with a time limit ended.
struct Timed {
  Finished f;
  int term_signal = 0;      // the signal that killed it (0: it exited)
  bool stopped = false;     // the limit was reached: SIGTERM sent
  bool hung = false;        // still alive one second after SIGTERM: SIGKILL sent
  double seconds = 0;       // from start to exit
  double after_stop = 0;    // from SIGTERM to exit
  long max_rss_kb = 0;      // peak resident memory
};

// Waits for `s` with a limit of `limit` seconds (then SIGTERM; then, after one second, SIGKILL).
inline Timed wait_timed(const Spawned& s, double limit) {
  Timed r;
  const auto t0 = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point t_stop{};
  int status = 0;
  struct rusage ru {};
  for (;;) {
    const pid_t done = wait4(s.pid, &status, WNOHANG, &ru);
    if (done == s.pid) break;
    const double now = seconds_since(t0);
    if (!r.stopped && now > limit) {
      kill(s.pid, SIGTERM);
      r.stopped = true;
      t_stop = std::chrono::steady_clock::now();
    } else if (r.stopped && !r.hung && seconds_since(t_stop) > 1.0) {
      kill(s.pid, SIGKILL);
      r.hung = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  r.seconds = seconds_since(t0);
  if (r.stopped) r.after_stop = seconds_since(t_stop);
  r.f.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.term_signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  r.f.out = slurp(s.out);
  r.f.err = slurp(s.err);
  r.max_rss_kb = ru.ru_maxrss;
  return r;
}

inline Timed run_timed(const std::filesystem::path& binary, const std::vector<std::string>& args,
                       const std::filesystem::path& log_dir, double limit, const Environment& env = {}) {
  return wait_timed(spawn(binary, args, log_dir, env), limit);
}

// Sends `sig` once `appears` exists (at most 60 s) and `settle` later; returns the time from the
// signal to the exit, and how it ended.
inline Timed signal_when(const Spawned& s, const std::filesystem::path& appears, int sig,
                         std::chrono::milliseconds settle = std::chrono::milliseconds(0)) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!std::filesystem::exists(appears) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(settle);
  const auto t0 = std::chrono::steady_clock::now();
  kill(s.pid, sig);
  Timed r = wait_timed(s, 30);
  r.after_stop = seconds_since(t0);
  return r;
}

}  // namespace sphark::test
