#pragma once
// Runs a built example program (build/bin/<name>, found next to this test's own build folder)
// with stdout and stderr captured.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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

// Starts `binary args...` with stdout/stderr redirected to files in `log_dir`.
inline Spawned spawn(const std::filesystem::path& binary, const std::vector<std::string>& args,
                     const std::filesystem::path& log_dir) {
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
    execv(argv[0], argv.data());
    _exit(127);
  }
  s.pid = pid;
  return s;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
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
                    const std::filesystem::path& log_dir) {
  return wait_for(spawn(binary, args, log_dir));
}

}  // namespace sphark::test
