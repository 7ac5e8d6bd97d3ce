// Ghost particles at curved walls: static reproduction of seed 004 (Fig. 5, Figs. 6-8, Table 1).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "ghost_static.hpp"
#include "sphark/io/visualise.hpp"

namespace {

void usage() {
  std::printf(
      "ghost_static: ghost particles at curved walls, static tests of seed 004 (Figs. 5-8, Table 1)\n"
      "  --out DIR             output directory (default out/ghost_static)\n"
      "  --particles N         relaxed inner particles per geometry, Figs. 6-8 (default 50000, min 2000)\n"
      "  --cost-particles N    random inner particles for Table 1 (default 1000000)\n"
      "  --draws N             random draws for Table 1 (default 10)\n"
      "  --seed S              random seed (default 1)\n"
      "  --no-plots            do not run vis/ghost_static.py at the end\n"
      "  --only PART           run one part: fig5, static or cost (default: all)\n"
      "  --relax-map MAP       ghosts in the near-wall relaxation: psi (default) or mirror\n"
      "  --help                this text\n");
}

[[noreturn]] void bad(const std::string& option, const std::string& value, const char* why) {
  std::fprintf(stderr, "ghost_static: bad value for %s: '%s' (%s)\n", option.c_str(), value.c_str(), why);
  std::exit(2);
}

unsigned long long parse_count(const std::string& option, const std::string& value, unsigned long long min,
                               unsigned long long max) {
  std::size_t used = 0;
  unsigned long long v = 0;
  try {
    if (value.empty() || value[0] == '-') throw std::invalid_argument("negative");
    v = std::stoull(value, &used);
  } catch (const std::exception&) {
    bad(option, value, "expected a non-negative integer");
  }
  if (used != value.size()) bad(option, value, "expected a non-negative integer");
  if (v < min || v > max)
    bad(option, value, ("expected " + std::to_string(min) + ".." + std::to_string(max)).c_str());
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  ghost_static::Options opt;
  std::string only;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) bad(a, "", "missing value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      usage();
      return 0;
    } else if (a == "--out") {
      opt.out = value();
      if (opt.out.empty()) bad(a, opt.out, "empty path");
    } else if (a == "--particles") {
      opt.particles = parse_count(a, value(), 2000, 5000000);
    } else if (a == "--cost-particles") {
      opt.cost_particles = parse_count(a, value(), 1000, 100000000);
    } else if (a == "--draws") {
      opt.draws = static_cast<int>(parse_count(a, value(), 2, 1000));
    } else if (a == "--seed") {
      opt.seed = static_cast<unsigned>(parse_count(a, value(), 0, 4294967295ull));
    } else if (a == "--only") {
      only = value();
      if (only != "fig5" && only != "static" && only != "cost") bad(a, only, "expected fig5, static or cost");
    } else if (a == "--relax-map") {
      const std::string m = value();
      if (m != "psi" && m != "mirror") bad(a, m, "expected psi or mirror");
      opt.relax_with_mirror = m == "mirror";
    } else if (a == "--no-plots") {
      opt.plots = false;
    } else {
      std::fprintf(stderr, "ghost_static: unknown option '%s' (see --help)\n", a.c_str());
      return 2;
    }
  }
  std::error_code ec;
  std::filesystem::create_directories(opt.out, ec);
  if (ec) bad("--out", opt.out, ec.message().c_str());

  const auto t0 = std::chrono::steady_clock::now();
  try {
    if (only.empty() || only == "fig5") ghost_static::write_fig5(opt);
    if (only.empty() || only == "static") ghost_static::run_static(opt);
    if (only.empty() || only == "cost") ghost_static::run_cost_table(opt);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ghost_static: error: %s\n", e.what());
    return 1;
  }
  std::printf("total %.1f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());

  if (opt.plots) {
    std::printf("/usr/bin/python3 vis/ghost_static.py %s\n", opt.out.c_str());
    std::fflush(stdout);
    if (!sphark::run_python("ghost_static.py", {opt.out}, false)) return 1;  // warning printed
  }
  return 0;
}
