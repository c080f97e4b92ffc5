// The rate-distortion benchmark's results: one row per (shape, method,
// setting), printed as a markdown table per shape and written as CSV for
// scripts/plot-rd.py.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace dbss::bench {

struct RdRow {
  std::string shape, method, setting;  // e.g. "armadillo", "dbss" / "advancing front", "L3" / "qp 11"
  uint64_t bytes = 0;                  // dbss: the file prefix that decodes the level; peers: the Draco file
  double error = 0;                    // two-sided mean distance to the true mesh over its bounding-box diagonal
  size_t vertices = 0, triangles = 0;
  double seconds = 0;                  // dbss: the whole encode; peers: reconstruction plus Draco encode
};

// dbss's bytes at `error` on its log-log curve of bytes against error:
// interpolated between the last level above `error` and the first at or
// below it.  The level-0 bytes when level 0 is already as good (an upper
// bound, `*at_most` set); NaN when no level reaches it.
double dbss_bytes_at(const std::vector<RdRow>& dbss_rows, double error, bool* at_most);

// Markdown: a heading for the shape, then its dbss rows and its peers' rows,
// each peer with the bytes dbss needs for the same error and their ratio.
void print_table(std::FILE* out, const std::string& heading, const std::vector<RdRow>& rows);

// Appends rows to a CSV file (header first when `with_header`); false when it
// cannot be written.
bool write_csv(const std::string& path, const std::vector<RdRow>& rows, bool with_header);

}  // namespace dbss::bench
