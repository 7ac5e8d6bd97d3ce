// --seeds K: Tables 4-5 depend on one random draw; repeat them over K nested random sets.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "sphark/io/atomic_file.hpp"
#include "scene.hpp"

namespace scene {

using namespace sphark::d1;

void seed_statistics(int table, const Options& opt, const std::vector<Index>& sizes) {
  const TableSpec spec = paper_table(table);
  std::map<std::pair<Method, Index>, std::vector<Real>> e;  // (method, N) -> e_N per seed
  std::map<Index, int> icspm_wins;                          // seeds where ICSPM has the smallest e_N
  for (int s = 0; s < opt.seeds; ++s) {
    const std::vector<TableRow> rows = compute_table(spec, sizes, opt.seed + s, seed_function());
    std::map<Index, std::map<Method, Real>> at;
    for (const TableRow& r : rows) {
      e[{r.method, r.n}].push_back(r.error);
      at[r.n][r.method] = r.error;
    }
    for (auto& [n, m] : at)
      if (m[Method::Icspm] <= std::min(m[Method::Cspm], m[Method::Bim])) ++icspm_wins[n];
  }
  const auto file = opt.out / ("table" + std::to_string(table) + "_seeds.csv");
  sphark::AtomicFile out(file);
  out << "method,N,seeds,mean_e_N,std_e_N,min_e_N,median_e_N,max_e_N,geomean_e_N,p_geomean\n";
  std::printf("\nTable %d over %d random sets (seeds %llu..%llu): e_N mean ± std [min, max], p from geometric means\n\n",
              table, opt.seeds, static_cast<unsigned long long>(opt.seed),
              static_cast<unsigned long long>(opt.seed + opt.seeds - 1));
  std::printf("| method | N | mean e_N | std | min | median | max | geo-mean | p (geo) | ICSPM best in |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Column& col : spec.columns) {
    Real previous_geo = NAN;
    for (Index n : sizes) {
      std::vector<Real> v = e[{col.method, n}];
      std::sort(v.begin(), v.end());
      Real mean = 0, lg = 0, var = 0;
      for (Real x : v) mean += x, lg += std::log(x);
      mean /= v.size();
      const Real geo = std::exp(lg / v.size());
      for (Real x : v) var += (x - mean) * (x - mean);
      const Real sd = v.size() > 1 ? std::sqrt(var / (v.size() - 1)) : 0.0;
      const Real median = v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
      const Real p = observed_order(previous_geo, geo);
      previous_geo = geo;
      char line[256];
      std::snprintf(line, sizeof line, "%s,%ld,%d,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%s\n", method_name(col.method),
                    static_cast<long>(n), opt.seeds, mean, sd, v.front(), median, v.back(), geo,
                    std::isnan(p) ? "" : std::to_string(p).c_str());
      out << line;
      std::printf("| %s | %ld | %.3e | %.2e | %.3e | %.3e | %.3e | %.3e | %s | %d/%d |\n", method_name(col.method),
                  static_cast<long>(n), mean, sd, v.front(), median, v.back(), geo,
                  std::isnan(p) ? "" : (std::to_string(std::round(p * 100) / 100).substr(0, 5)).c_str(),
                  icspm_wins[n], opt.seeds);
    }
  }
  out.commit();
}

}  // namespace scene
