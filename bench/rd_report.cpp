// Tables and CSV of the rate-distortion benchmark.
#include "rd_report.h"

#include <cmath>
#include <limits>

namespace dbss::bench {

double dbss_bytes_at(const std::vector<RdRow>& dbss_rows, double error, bool* at_most) {
  *at_most = false;
  for (size_t i = 0; i < dbss_rows.size(); ++i) {
    const RdRow& r = dbss_rows[i];
    if (!(r.error <= error)) continue;
    if (i == 0) {
      *at_most = true;
      return static_cast<double>(r.bytes);
    }
    // Straight line in log(bytes) against log(error) between the level
    // before (worse than `error`) and this one.
    const RdRow& p = dbss_rows[i - 1];
    const double t = (std::log(error) - std::log(p.error)) / (std::log(r.error) - std::log(p.error));
    return std::exp(std::log(double(p.bytes)) + t * (std::log(double(r.bytes)) - std::log(double(p.bytes))));
  }
  return std::numeric_limits<double>::quiet_NaN();
}

void print_table(std::FILE* out, const std::string& heading, const std::vector<RdRow>& rows) {
  std::vector<RdRow> dbss;
  for (const RdRow& r : rows)
    if (r.method == "dbss") dbss.push_back(r);
  std::fprintf(out, "\n%s\n\n", heading.c_str());
  std::fprintf(out, "| method | setting | KB | error | vertices | triangles | seconds | dbss KB at this error | dbss / peer |\n");
  std::fprintf(out, "|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const RdRow& r : rows) {
    std::fprintf(out, "| %s | %s | %.1f | %.2e | %zu | %zu | %.2f |", r.method.c_str(), r.setting.c_str(), r.bytes / 1000.0,
                 r.error, r.vertices, r.triangles, r.seconds);
    if (r.method == "dbss" || dbss.empty()) {
      std::fprintf(out, " | |\n");
      continue;
    }
    bool at_most = false;
    const double b = dbss_bytes_at(dbss, r.error, &at_most);
    if (std::isnan(b))
      std::fprintf(out, " not reached | |\n");
    else
      std::fprintf(out, " %s%.1f | %s%.2f |\n", at_most ? "≤ " : "", b / 1000.0, at_most ? "≤ " : "", b / double(r.bytes));
  }
}

bool write_csv(const std::string& path, const std::vector<RdRow>& rows, bool with_header) {
  std::FILE* f = std::fopen(path.c_str(), with_header ? "w" : "a");
  if (f == nullptr) return false;
  if (with_header) std::fprintf(f, "shape,method,setting,bytes,error,vertices,triangles,seconds\n");
  // Method and setting names hold no commas or quotes, so no quoting.
  for (const RdRow& r : rows)
    std::fprintf(f, "%s,%s,%s,%llu,%.6e,%zu,%zu,%.3f\n", r.shape.c_str(), r.method.c_str(), r.setting.c_str(),
                 static_cast<unsigned long long>(r.bytes), r.error, r.vertices, r.triangles, r.seconds);
  return std::fclose(f) == 0;
}

}  // namespace dbss::bench
