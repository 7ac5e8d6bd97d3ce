#pragma once
// Pictures from C++: runs a script from the source tree's vis/ folder with /usr/bin/python3.
// Never aborts a finished run: any failure is one warning line on stderr and a false return.
#include <filesystem>
#include <string>
#include <vector>

namespace sphark {

// The vis/ folder of the source tree (SPHARK_SOURCE_DIR "/vis").
std::filesystem::path vis_dir();

// Runs `/usr/bin/python3 <vis_dir()/script> args...` (no shell: arguments are passed as they
// are). If needs_display and $DISPLAY is unset or empty, runs it under `xvfb-run -a`.
// Returns true iff the script exited with status 0. On failure (script or python or xvfb-run
// missing, non-zero exit, killed, or still running after timeout_seconds, when its process
// group is killed) prints one line "sphark: warning: vis/<script>: ..." to stderr.
bool run_python(const std::string& script_relative_to_vis, const std::vector<std::string>& args,
                bool needs_display, double timeout_seconds = 600);

// One picture script of vis/ with its arguments, for run_python_batch().
struct PythonJob {
  std::string script;  // e.g. "charts.py"
  std::vector<std::string> args;
};

// Every job in one Python batch (vis/batch.py): matplotlib, VTK and xvfb-run start once for
// all of them, then the jobs are spread over `processes` forked workers (0: every core this
// process may use; 1: one after the other). Every job runs even if an earlier one failed; true
// iff all succeeded (a failed job is one line on stderr, then the warning of run_python).
bool run_python_batch(const std::vector<PythonJob>& jobs, bool needs_display, double timeout_seconds = 600,
                      int processes = 0);

struct ProcessResult {
  bool ok = false;    // started and exited with status 0
  std::string error;  // otherwise why: "cannot start ...", "exited with status 2", ...
};

// Runs argv[0] (a path; no $PATH search, no shell) with argv in its own process group, waits
// at most timeout_seconds, then kills the group (SIGTERM, SIGKILL after 2 s).
ProcessResult run_process(const std::vector<std::string>& argv, double timeout_seconds);

}  // namespace sphark
