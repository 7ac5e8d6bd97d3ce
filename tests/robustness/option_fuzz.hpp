#pragma once
// The option fuzz of tests/robustness/option_fuzz_test.cpp: the options of an example read
// from its --help, a table of hostile values per option type, each case run with a time limit in
// a folder of its own, and the verdict on how it ended (docs/robustness.md, "Option fuzz").
#include <algorithm>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "run_example.hpp"

namespace sphark::test {

struct HelpOption {
  std::string name;     // "--t-end"
  std::string metavar;  // "REAL", "INT", "NAME", "DIR", "FILE", "PATH", "LIST", "on|off"; "" for a flag
};

// The options of `help` (an OptionParser's --help text): lines "  --name [METAVAR]  text".
inline std::vector<HelpOption> parse_help(const std::string& help) {
  std::vector<HelpOption> out;
  const std::regex line(R"(^  (--[A-Za-z0-9-]+)(?: ([^ ]+))?  )");
  std::istringstream in(help);
  for (std::string l; std::getline(in, l);) {
    std::smatch m;
    if (std::regex_search(l, m, line)) out.push_back({m[1], m[2]});
  }
  return out;
}

// Hostile values for an option of this metavar: non-finite, negative, zero, tiny, enormous,
// out of range, mistyped (letters, a decimal comma, a fraction for an integer) and empty.
inline std::vector<std::string> hostile_values(const std::string& metavar) {
  if (metavar == "REAL") return {"nan", "inf", "-1", "0", "1e-300", "1e300", "1e400", "abc", "1,5", ""};
  if (metavar == "INT")
    return {"-1", "0", "1", "2147483647", "2147483648", "99999999999999999999", "1.5", "abc", "nan", ""};
  if (metavar == "LIST") return {"nan", "1,,2", ",", "-1", "0", "1e-300", "1e300", "abc", ""};
  if (metavar == "on|off") return {"maybe", "ON", "1", ""};
  if (metavar == "DIR" || metavar == "PATH") return {"", "/proc/sphark_fuzz", "a_file/sub", "/dev/null"};
  if (metavar == "FILE") return {"", "/dev/null", "/nonexistent/x.bin", "garbage.bin", "bad_value.json", "unknown_key.json"};
  return {"", "nonexistent", "NONE", "1e300", "all,none"};  // NAME: a name or a free-form list
}

// Files every case folder holds before the case runs (its working directory).
inline void prepare_case_dir(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "a_file") << "x";
  std::ofstream(dir / "garbage.bin", std::ios::binary) << std::string("SPHARKCK\x02\0\0\0garbage", 20);
  std::ofstream(dir / "bad_value.json") << R"({"t-end": "abc"})";
  std::ofstream(dir / "unknown_key.json") << R"({"no-such-option": 1})";
}
inline const std::set<std::string>& case_dir_files() {
  static const std::set<std::string> f = {"a_file", "garbage.bin", "bad_value.json", "unknown_key.json", "stdout.txt",
                                          "stderr.txt"};
  return f;
}

struct FuzzCase {
  std::string program;
  std::vector<std::string> base;   // the tiny, short run every case starts from
  std::vector<std::string> typed;  // what is added (last: it overrides the base)
  bool handles_signals = true;     // time-integrating programs stop on SIGTERM with exit 143
};

struct FuzzOutcome {
  std::size_t index = 0;  // of the case in the generated table
  FuzzCase c;
  Timed r;
  std::vector<std::string> stray;  // files a rejected case left in its folder
  std::string verdict;             // "" ok, else what is wrong
  std::string what;                // what happens now (for the table)
};

inline std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& a : v) {
    if (!s.empty()) s += ' ';
    s += a.empty() ? "''" : a;
  }
  return s;
}

inline std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

// The verdict (allowed: exit 0 ran; 2 rejected before anything was written, one line; 3 failed
// cleanly; stopped at the limit by SIGTERM and gone within a second: exit 143, or killed by the
// signal for a program without stop handlers) and what happened, for the table.
inline void judge(FuzzOutcome& o, const std::filesystem::path& case_dir, double limit) {
  // the study's testing aid --raise-sigint-after N sends itself SIGINT: exit 130 is what it asks for
  const bool asks_for_sigint = !o.c.typed.empty() && o.c.typed.front() == "--raise-sigint-after";
  const Timed& r = o.r;
  const std::string prefix = o.c.program + ": ";
  std::string err = first_line(r.f.err);
  if (err.rfind(prefix, 0) == 0) err = err.substr(prefix.size());
  char buf[160];
  if (r.hung) {
    o.verdict = "hang: alive 1 s after SIGTERM";
    o.what = "HANG";
  } else if (r.stopped) {
    const bool ok = o.c.handles_signals ? r.f.exit_code == 128 + SIGTERM : r.term_signal == SIGTERM || r.f.exit_code == 128 + SIGTERM;
    std::snprintf(buf, sizeof buf, "long run: SIGTERM at the %.0f s limit, gone %.2f s later (%s)", limit, r.after_stop,
                  r.term_signal ? "killed by it: no stop handler" : ("exit " + std::to_string(r.f.exit_code)).c_str());
    o.what = buf;
    if (!ok) o.verdict = "did not stop cleanly on SIGTERM";
    if (r.after_stop > 1.0) o.verdict = "took more than 1 s to stop";
  } else if (r.term_signal != 0) {
    o.verdict = "crashed with signal " + std::to_string(r.term_signal);
    o.what = "CRASH (signal " + std::to_string(r.term_signal) + ")";
  } else if (r.f.exit_code == 0) {
    std::snprintf(buf, sizeof buf, "ran (%.1f s)", r.seconds);
    o.what = buf;
  } else if (r.f.exit_code == 128 + SIGINT && asks_for_sigint) {
    o.what = "stopped by its own SIGINT (testing aid), exit 130";
  } else if (r.f.exit_code == 3) {
    const std::size_t at = r.f.err.find(" FAILED at ");  // the time loop's report, else the last line
    std::string why = at != std::string::npos ? first_line(r.f.err.substr(r.f.err.rfind('\n', at) + 1))
                                              : first_line(r.f.err.substr(r.f.err.rfind('\n', r.f.err.size() - 2) + 1));
    if (why.rfind(prefix, 0) == 0) why = why.substr(prefix.size());
    o.what = "failed cleanly: " + why.substr(0, 130);
  } else if (r.f.exit_code == 2) {
    o.what = err.substr(0, 140);
    const std::size_t lines = static_cast<std::size_t>(std::count(r.f.err.begin(), r.f.err.end(), '\n'));
    if (lines != 1) o.verdict = "rejected with " + std::to_string(lines) + " lines";
    for (const auto& e : std::filesystem::directory_iterator(case_dir))
      if (!case_dir_files().count(e.path().filename().string())) o.stray.push_back(e.path().filename().string());
    if (!o.stray.empty()) o.verdict = "rejected but wrote " + joined(o.stray);
  } else {
    o.verdict = "exit " + std::to_string(r.f.exit_code);
    o.what = "EXIT " + std::to_string(r.f.exit_code) + ": " + err.substr(0, 110);
  }
}

namespace fs = std::filesystem;
inline constexpr double kLimit = 5;  // seconds per case before SIGTERM
inline constexpr std::size_t kParallel = 2;

struct Running {
  std::size_t index = 0;
  FuzzCase c;
  fs::path dir;
  Spawned s;
  std::chrono::steady_clock::time_point start, stop_sent;
  bool stopped = false, killed = false;
};

// Polls a running case; true once it has ended (its outcome in `out`).
inline bool poll(Running& run, FuzzOutcome& out) {
  int status = 0;
  struct rusage ru {};
  if (wait4(run.s.pid, &status, WNOHANG, &ru) != run.s.pid) {
    if (!run.stopped && seconds_since(run.start) > kLimit) {
      kill(run.s.pid, SIGTERM);
      run.stopped = true;
      run.stop_sent = std::chrono::steady_clock::now();
    } else if (run.stopped && !run.killed && seconds_since(run.stop_sent) > 1.0) {
      kill(run.s.pid, SIGKILL);
      run.killed = true;
    }
    return false;
  }
  Timed& r = out.r;
  r.seconds = seconds_since(run.start);
  r.stopped = run.stopped;
  r.hung = run.killed;
  if (run.stopped) r.after_stop = seconds_since(run.stop_sent);
  r.f.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.term_signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  r.f.out = slurp(run.s.out);
  r.f.err = slurp(run.s.err);
  out.c = run.c;
  judge(out, run.dir, kLimit);
  return true;
}

// Runs every case, kParallel at a time, each in root/case_<k> (kept only if its verdict is bad).
inline std::vector<FuzzOutcome> run_all(const std::vector<FuzzCase>& cases, const fs::path& root) {
  std::vector<FuzzOutcome> done;
  std::vector<Running> running;
  std::size_t next = 0;
  while (next < cases.size() || !running.empty()) {
    while (running.size() < kParallel && next < cases.size()) {
      Running r;
      r.index = next;
      r.c = cases[next];
      r.dir = root / ("case_" + std::to_string(next++));
      prepare_case_dir(r.dir);
      std::vector<std::string> args{"--out", (r.dir / "out").string()};
      args.insert(args.end(), r.c.base.begin(), r.c.base.end());
      args.insert(args.end(), r.c.typed.begin(), r.c.typed.end());
      r.start = std::chrono::steady_clock::now();
      r.s = spawn(require_example(r.c.program), args, r.dir, {}, r.dir);
      running.push_back(std::move(r));
    }
    for (std::size_t k = 0; k < running.size();) {
      FuzzOutcome o;
      if (!poll(running[k], o)) {
        ++k;
        continue;
      }
      if (o.verdict.empty()) fs::remove_all(running[k].dir);  // kept for a failure
      o.index = running[k].index;
      done.push_back(std::move(o));
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  std::sort(done.begin(), done.end(), [](const FuzzOutcome& a, const FuzzOutcome& b) { return a.index < b.index; });
  return done;
}

}  // namespace sphark::test
