#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "sphark/io/atomic_file.hpp"
#include "scene.hpp"

namespace scene {

using namespace sphark::d1;

void write_table_csv(const std::filesystem::path& file, const std::vector<TableRow>& rows) {
  sphark::AtomicFile out(file);
  out << "method,N,e_N,p_N\n";
  char line[128];
  for (const TableRow& r : rows) {
    if (std::isnan(r.order))
      std::snprintf(line, sizeof line, "%s,%ld,%.6e,\n", method_name(r.method), static_cast<long>(r.n), r.error);
    else
      std::snprintf(line, sizeof line, "%s,%ld,%.6e,%.4f\n", method_name(r.method), static_cast<long>(r.n), r.error,
                    r.order);
    out << line;
  }
  out.commit();
}

void print_table_markdown(const std::string& title, const std::vector<TableRow>& rows) {
  std::vector<Method> methods;
  std::map<Index, std::map<Method, const TableRow*>> by_n;
  for (const TableRow& r : rows) {
    if (methods.empty() || methods.back() != r.method) methods.push_back(r.method);
    by_n[r.n][r.method] = &r;
  }
  std::printf("\n%s\n\n| N |", title.c_str());
  for (Method m : methods) std::printf(" %s e_N | p_N |", method_name(m));
  std::printf("\n|---:|");
  for (std::size_t k = 0; k < methods.size(); ++k) std::printf("---:|---:|");
  std::printf("\n");
  for (const auto& [n, row] : by_n) {
    std::printf("| %ld |", static_cast<long>(n));
    for (Method m : methods) {
      const TableRow* r = row.at(m);
      if (std::isnan(r->order))
        std::printf(" %.6e | |", r->error);
      else
        std::printf(" %.6e | %.4f |", r->error, r->order);
    }
    std::printf("\n");
  }
}

}  // namespace scene
