#include "info.h"
#include "info_report.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "dbss/format/reader.h"
#include "dbss/io/file.h"
#include "fnv1a.h"

namespace dbss::tools {

namespace {

constexpr const char* kHelp =
    "usage: dbss info IN.dbss [--json] [--hashes]\n"
    "\n"
    "Reads a .dbss file and verifies everything 'dbss decode' verifies: every\n"
    "chunk's CRC32C and fields, the decompressed displacements, and the control\n"
    "mesh (Draco-decoded, its counts against the header, its manifold checks).\n"
    "It prints the chunks (offset, length, status), the header, per-level vertex\n"
    "and triangle counts, quantization steps and bits per displacement.  It does\n"
    "not subdivide (a verified file cannot fail there) unless --hashes is given.\n"
    "A damaged or truncated file prints what was verified, then the error; the\n"
    "levels verified before the damage stay usable (spec section 11).\n"
    "\n"
    "  --json     one JSON object on stdout instead of tables\n"
    "  --hashes   decode every verified level and print only, per level, the line\n"
    "             'level L vertices V triangles T fnv1a64 HEX' (spec/decoding.md\n"
    "             section 8); with --json, each level gets an \"fnv1a64\" field\n"
    "\n"
    "exit status: 0 file is complete and valid (a malformed 'meta' chunk is only a\n"
    "warning), 1 bad file or usage, 2 internal error\n";

}  // namespace

int run_info(const std::vector<std::string_view>& args) {
  std::string path;
  bool json = false, hashes = false;
  for (std::string_view a : args) {
    if (a == "--help" || a == "-h") {
      std::fputs(kHelp, stdout);
      return 0;
    } else if (a == "--json") {
      json = true;
    } else if (a == "--hashes") {
      hashes = true;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "dbss info: unknown option '%.*s'\n\n%s", static_cast<int>(a.size()), a.data(), kHelp);
      return 1;
    } else if (path.empty()) {
      path = a;
    } else {
      std::fprintf(stderr, "dbss info: more than one input file\n\n%s", kHelp);
      return 1;
    }
  }
  if (path.empty()) {
    std::fprintf(stderr, "dbss info: no input file\n\n%s", kHelp);
    return 1;
  }
  const format::Limits limits;
  auto bytes = io::read_file(path, limits.max_file_size);
  if (!bytes.ok()) {
    std::fprintf(stderr, "dbss info: %s\n", bytes.status().message().c_str());
    return 1;
  }
  const InfoReport rep = inspect_bytes(bytes.value(), hashes, limits);
  const format::Reader& r = rep.reader();
  const Status& control = rep.control;
  const std::vector<uint64_t>& level_hash = rep.level_hash;
  const std::vector<InfoChunkRow>& rows = rep.rows;
  const std::vector<uint64_t>& level_bytes = rep.level_bytes;
  const bool valid = rep.valid;
  const Status& first_error = rep.first_error;
  const format::Header& h = r.header();
  const format::MeshCounts control_counts{h.control_vertex_count, h.control_edge_count, h.control_triangle_count};

  if (json) {
    std::fputs(info_json(rep, path).c_str(), stdout);
  } else if (hashes) {
    // Only these lines, so outputs of different implementations compare with diff.
    for (uint32_t l = 0; l < level_hash.size(); ++l) {
      const auto c = format::counts_at_level(control_counts, l);
      std::printf("level %u vertices %llu triangles %llu fnv1a64 %s\n", l,
                  static_cast<unsigned long long>(c->vertices), static_cast<unsigned long long>(c->triangles),
                  fnv1a64_hex(level_hash[l]).c_str());
    }
  } else {
    std::printf("%s: %zu bytes, %s\n", path.c_str(), bytes.value().size(),
                valid ? "complete, every chunk verified" : "NOT complete");
    if (r.has_header()) {
      std::printf("format %u.%u, %u levels, control mesh %u vertices / %u edges / %u triangles (Draco, %u-bit positions)\n",
                  h.version_major, h.version_minor, h.level_count, h.control_vertex_count, h.control_edge_count,
                  h.control_triangle_count, h.control_position_bits);
      std::printf("bbox [%g %g %g] .. [%g %g %g], error target %g of the diagonal\n", h.bbox_min[0], h.bbox_min[1],
                  h.bbox_min[2], h.bbox_max[0], h.bbox_max[1], h.bbox_max[2], h.error_target);
    }
    std::printf("\n%-6s %12s %12s  %s\n", "chunk", "offset", "length", "status");
    for (const InfoChunkRow& row : rows)
      std::printf("%-6s %12llu %12llu  %s\n", row.type.c_str(), static_cast<unsigned long long>(row.offset),
                  static_cast<unsigned long long>(row.length), row.verified                             ? "verified"
                  : row.type == "CTRL" && r.has_control() ? "bad mesh"
                                                          : "missing");
    if (r.has_header()) {
      std::printf("\n%-5s %12s %12s %12s %12s %-11s %10s %8s\n", "level", "vertices", "triangles", "odd", "step",
                  "coding", "bytes", "bits/odd");
      for (uint32_t l = 0; l <= h.level_count; ++l) {
        const auto c = format::counts_at_level(control_counts, l);
        std::printf("%-5u %12llu %12llu", l, static_cast<unsigned long long>(c->vertices),
                    static_cast<unsigned long long>(c->triangles));
        if (l == 0) {
          std::printf(" %12s %12s %-11s %10s %8s\n", "-", "-", "draco", "",
                      !r.has_control() ? "(missing)" : control.ok() ? "" : "(bad)");
        } else if (l <= r.levels_ready()) {
          const auto& lv = r.level(l);
          // (bytes include the level's BDRY chunk: its cost per odd vertex)
          const double bits = lv.q.empty() ? 0.0 : 8.0 * static_cast<double>(level_bytes[l - 1]) / lv.q.size();
          std::printf(" %12zu %12.6g %-11s %10llu %8.3f\n", lv.q.size(), lv.step, format::coding_name(lv.coding),
                      static_cast<unsigned long long>(level_bytes[l - 1]), bits);
        } else {
          std::printf(" %12s %12s %-11s %10s %8s\n", "-", "-", "(missing)", "", "");
        }
      }
    }
    if (!r.metadata().empty()) {
      std::printf("\nmetadata:\n");
      for (const auto& m : r.metadata()) std::printf("  %s = %s\n", m.key.c_str(), m.value.c_str());
    }
  }
  for (const Status& w : r.warnings())
    std::fprintf(stderr, "dbss info: warning: %s: %s (ignored)\n", path.c_str(), w.to_string().c_str());
  if (!valid) {
    std::fprintf(stderr, "dbss info: %s: %s\n", path.c_str(), first_error.to_string().c_str());
    if (!r.status().ok() && r.has_control() && !control.ok())
      std::fprintf(stderr, "dbss info: %s: %s\n", path.c_str(), control.to_string().c_str());
    if (r.failed() && control.ok())
      std::fprintf(stderr, "dbss info: %s: levels 0..%u were verified before the error and are usable\n",
                   path.c_str(), r.levels_ready());
    return 1;
  }
  return 0;
}

}  // namespace dbss::tools
