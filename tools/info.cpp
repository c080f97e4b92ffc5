#include "info.h"
#include "json.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "dbss/decoder/progressive.h"
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

const char* coding_name(format::DisplacementCoding c) {
  return c == format::DisplacementCoding::byte_planes ? "byte_planes" : "varint";
}

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
  DecoderOptions options;
  options.limits = limits;
  ProgressiveDecoder d(options);
  d.feed(bytes.value());
  d.finish();
  const format::Reader& r = d.reader();
  // The control mesh is checked as decode checks it (spec/decoding.md
  // section 2), so info cannot pass a file that decode refuses.
  Status control = r.has_control() ? Status() : Status(ErrorCode::truncated, "no control mesh");
  if (r.has_control()) {
    auto mesh = d.decode(0);
    if (!mesh.ok()) control = mesh.status();
  }
  // Per-level FNV-1a of the decoded positions (spec/decoding.md section 8).
  std::vector<uint64_t> level_hash;
  if (hashes && control.ok()) {
    for (int l = 0; l <= d.ready_level(); ++l) {
      auto mesh = d.decode(static_cast<uint32_t>(l));
      if (!mesh.ok()) {
        control = mesh.status();
        break;
      }
      level_hash.push_back(fnv1a64_floats(mesh.value().positions));
    }
  }
  const bool valid = r.complete() && control.ok();
  const Status first_error = !r.status().ok() ? r.status() : control;
  const format::Header& h = r.header();
  const format::MeshCounts control_counts{h.control_vertex_count, h.control_edge_count, h.control_triangle_count};

  // Chunk rows: HEAD and INDX, then the table of contents.
  struct Row {
    std::string type;
    uint64_t offset, length;
    bool verified;
  };
  std::vector<Row> rows;
  if (r.has_header()) rows.push_back({"HEAD", 8, format::kHeadSize, true});
  if (r.has_toc()) {
    const uint64_t toc_len = 16 + 16 * r.toc().size();
    rows.push_back({"INDX", 8 + format::kChunkOverhead + format::kHeadSize, toc_len, true});
    for (size_t i = 0; i < r.toc().size(); ++i) {
      const auto& e = r.toc()[i];
      const bool bad_mesh = e.type == format::kCtrl && r.has_control() && !control.ok();
      rows.push_back({e.type.str(), e.offset, e.length, i < r.chunks_verified() && !bad_mesh});
    }
  }
  // Compressed bytes per level, from the table of contents.
  std::vector<uint64_t> level_bytes;
  for (const auto& e : r.toc())
    if (e.type == format::kLevl) level_bytes.push_back(e.length);

  if (json) {
    std::printf("{\n  \"file\": %s,\n  \"bytes\": %zu,\n  \"complete\": %s,\n", json_string(path).c_str(),
                bytes.value().size(), valid ? "true" : "false");
    std::printf("  \"status\": %s,\n", json_string(first_error.to_string()).c_str());
    std::printf("  \"warnings\": [");
    for (size_t i = 0; i < r.warnings().size(); ++i)
      std::printf("%s%s", i ? ", " : "", json_string(r.warnings()[i].to_string()).c_str());
    std::printf("],\n");
    if (r.has_header()) {
      std::printf("  \"version\": \"%u.%u\",\n  \"levels\": %u,\n", h.version_major, h.version_minor, h.level_count);
      std::printf("  \"control\": {\"vertices\": %u, \"edges\": %u, \"triangles\": %u, \"position_bits\": %u},\n",
                  h.control_vertex_count, h.control_edge_count, h.control_triangle_count, h.control_position_bits);
      std::printf("  \"bbox_min\": [%.9g, %.9g, %.9g],\n  \"bbox_max\": [%.9g, %.9g, %.9g],\n", h.bbox_min[0],
                  h.bbox_min[1], h.bbox_min[2], h.bbox_max[0], h.bbox_max[1], h.bbox_max[2]);
      std::printf("  \"error_target\": %.9g,\n", h.error_target);
    }
    std::printf("  \"chunks\": [");
    for (size_t i = 0; i < rows.size(); ++i)
      std::printf("%s\n    {\"type\": %s, \"offset\": %llu, \"length\": %llu, \"verified\": %s}", i ? "," : "",
                  json_string(rows[i].type).c_str(), static_cast<unsigned long long>(rows[i].offset),
                  static_cast<unsigned long long>(rows[i].length), rows[i].verified ? "true" : "false");
    std::printf("\n  ],\n  \"level_table\": [");
    for (uint32_t l = 0; r.has_header() && l <= h.level_count; ++l) {
      const auto c = format::counts_at_level(control_counts, l);
      std::printf("%s\n    {\"level\": %u, \"vertices\": %llu, \"triangles\": %llu", l ? "," : "", l,
                  static_cast<unsigned long long>(c->vertices), static_cast<unsigned long long>(c->triangles));
      if (l >= 1 && l <= r.levels_ready()) {
        const auto& lv = r.level(l);
        std::printf(", \"odd\": %zu, \"step\": %.9g, \"coding\": \"%s\", \"bytes\": %llu", lv.q.size(), lv.step,
                    coding_name(lv.coding), static_cast<unsigned long long>(level_bytes[l - 1]));
      }
      if (l < level_hash.size())
        std::printf(", \"fnv1a64\": \"%s\"", fnv1a64_hex(level_hash[l]).c_str());
      std::printf(", \"ready\": %s}",
                  (l == 0 ? r.has_control() && control.ok() : control.ok() && l <= r.levels_ready()) ? "true"
                                                                                                       : "false");
    }
    std::printf("\n  ],\n  \"metadata\": {");
    for (size_t i = 0; i < r.metadata().size(); ++i)
      std::printf("%s%s: %s", i ? ", " : "", json_string(r.metadata()[i].key).c_str(),
                  json_string(r.metadata()[i].value).c_str());
    std::printf("}\n}\n");
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
    for (const Row& row : rows)
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
          const double bits = lv.q.empty() ? 0.0 : 8.0 * static_cast<double>(level_bytes[l - 1]) / lv.q.size();
          std::printf(" %12zu %12.6g %-11s %10llu %8.3f\n", lv.q.size(), lv.step, coding_name(lv.coding),
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
