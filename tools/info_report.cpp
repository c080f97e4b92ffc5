#include "info_report.h"

#include <cstdarg>
#include <cstdio>

#include "fnv1a.h"
#include "json.h"

namespace dbss::tools {

namespace {

// printf onto the end of `out`.
[[gnu::format(printf, 2, 3)]] void appendf(std::string& out, const char* fmt, ...) {
  va_list a, b;
  va_start(a, fmt);
  va_copy(b, a);
  const int n = std::vsnprintf(nullptr, 0, fmt, a);
  va_end(a);
  if (n > 0) {
    const size_t at = out.size();
    out.resize(at + static_cast<size_t>(n) + 1);
    std::vsnprintf(out.data() + at, static_cast<size_t>(n) + 1, fmt, b);
    out.resize(at + static_cast<size_t>(n));
  }
  va_end(b);
}

}  // namespace

InfoReport inspect_bytes(std::span<const uint8_t> bytes, bool hashes, const format::Limits& limits) {
  DecoderOptions options;
  options.limits = limits;
  InfoReport rep;
  rep.decoder = ProgressiveDecoder(options);
  rep.file_bytes = bytes.size();
  ProgressiveDecoder& d = rep.decoder;
  d.feed(bytes);
  d.finish();
  const format::Reader& r = d.reader();
  // The control mesh is checked as decode checks it (spec/decoding.md
  // section 2), so info cannot pass a file that decode refuses.
  rep.control = r.has_control() ? Status() : Status(ErrorCode::truncated, "no control mesh");
  if (r.has_control()) {
    auto mesh = d.decode(0);
    if (!mesh.ok()) rep.control = mesh.status();
  }
  // Per-level FNV-1a of the decoded positions (spec/decoding.md section 8).
  if (hashes && rep.control.ok()) {
    for (int l = 0; l <= d.ready_level(); ++l) {
      auto mesh = d.decode(static_cast<uint32_t>(l));
      if (!mesh.ok()) {
        rep.control = mesh.status();
        break;
      }
      rep.level_hash.push_back(fnv1a64_floats(mesh.value().positions));
    }
  }
  rep.valid = r.complete() && rep.control.ok();
  rep.first_error = !r.status().ok() ? r.status() : rep.control;

  if (r.has_header()) rep.rows.push_back({"HEAD", 8, format::kHeadSize, true});
  if (r.has_toc()) {
    const uint64_t toc_len = 16 + 16 * r.toc().size();
    rep.rows.push_back({"INDX", 8 + format::kChunkOverhead + format::kHeadSize, toc_len, true});
    for (size_t i = 0; i < r.toc().size(); ++i) {
      const auto& e = r.toc()[i];
      const bool bad_mesh = e.type == format::kCtrl && r.has_control() && !rep.control.ok();
      rep.rows.push_back({e.type.str(), e.offset, e.length, i < r.chunks_verified() && !bad_mesh});
    }
  }
  // A level's BDRY chunk (format 1.3) comes just before its LEVL and is
  // part of what the level costs.
  uint64_t boundary = 0;
  for (const auto& e : r.toc()) {
    if (e.type == format::kBdry) boundary += e.length;
    if (e.type != format::kLevl) continue;
    rep.level_bytes.push_back(e.length + boundary);
    rep.boundary_bytes.push_back(boundary);
    boundary = 0;
  }
  return rep;
}

std::string info_json(const InfoReport& rep, const std::optional<std::string>& path) {
  const format::Reader& r = rep.reader();
  const format::Header& h = r.header();
  const format::MeshCounts control_counts{h.control_vertex_count, h.control_edge_count, h.control_triangle_count};
  std::string o;
  appendf(o, "{\n  \"file\": %s,\n  \"bytes\": %zu,\n  \"complete\": %s,\n",
          path ? json_string(*path).c_str() : "null", rep.file_bytes, rep.valid ? "true" : "false");
  appendf(o, "  \"status\": %s,\n", json_string(rep.first_error.to_string()).c_str());
  appendf(o, "  \"warnings\": [");
  for (size_t i = 0; i < r.warnings().size(); ++i)
    appendf(o, "%s%s", i ? ", " : "", json_string(r.warnings()[i].to_string()).c_str());
  appendf(o, "],\n");
  if (r.has_header()) {
    appendf(o, "  \"version\": \"%u.%u\",\n  \"levels\": %u,\n", h.version_major, h.version_minor, h.level_count);
    appendf(o, "  \"control\": {\"vertices\": %u, \"edges\": %u, \"triangles\": %u, \"position_bits\": %u},\n",
            h.control_vertex_count, h.control_edge_count, h.control_triangle_count, h.control_position_bits);
    appendf(o, "  \"bbox_min\": [%.9g, %.9g, %.9g],\n  \"bbox_max\": [%.9g, %.9g, %.9g],\n", h.bbox_min[0],
            h.bbox_min[1], h.bbox_min[2], h.bbox_max[0], h.bbox_max[1], h.bbox_max[2]);
    appendf(o, "  \"error_target\": %.9g,\n", h.error_target);
  }
  appendf(o, "  \"chunks\": [");
  for (size_t i = 0; i < rep.rows.size(); ++i)
    appendf(o, "%s\n    {\"type\": %s, \"offset\": %llu, \"length\": %llu, \"verified\": %s}", i ? "," : "",
            json_string(rep.rows[i].type).c_str(), static_cast<unsigned long long>(rep.rows[i].offset),
            static_cast<unsigned long long>(rep.rows[i].length), rep.rows[i].verified ? "true" : "false");
  appendf(o, "\n  ],\n  \"level_table\": [");
  for (uint32_t l = 0; r.has_header() && l <= h.level_count; ++l) {
    const auto c = format::counts_at_level(control_counts, l);
    appendf(o, "%s\n    {\"level\": %u, \"vertices\": %llu, \"triangles\": %llu", l ? "," : "", l,
            static_cast<unsigned long long>(c->vertices), static_cast<unsigned long long>(c->triangles));
    if (l >= 1 && l <= r.levels_ready()) {
      const auto& lv = r.level(l);
      appendf(o, ", \"odd\": %zu, \"step\": %.9g, \"coding\": \"%s\", \"bytes\": %llu", lv.q.size(), lv.step,
              format::coding_name(lv.coding), static_cast<unsigned long long>(rep.level_bytes[l - 1]));
      if (!lv.boundary.empty())
        appendf(o, ", \"boundary_values\": %zu, \"boundary_step\": %.9g, \"boundary_coding\": \"%s\", \"boundary_bytes\": %llu",
                lv.boundary.q.size(), lv.boundary.step, format::coding_name(lv.boundary.coding),
                static_cast<unsigned long long>(rep.boundary_bytes[l - 1]));
    }
    if (l < rep.level_hash.size()) appendf(o, ", \"fnv1a64\": \"%s\"", fnv1a64_hex(rep.level_hash[l]).c_str());
    const bool ready = l == 0 ? r.has_control() && rep.control.ok() : rep.control.ok() && l <= r.levels_ready();
    appendf(o, ", \"ready\": %s}", ready ? "true" : "false");
  }
  appendf(o, "\n  ],\n  \"metadata\": {");
  for (size_t i = 0; i < r.metadata().size(); ++i)
    appendf(o, "%s%s: %s", i ? ", " : "", json_string(r.metadata()[i].key).c_str(),
            json_string(r.metadata()[i].value).c_str());
  appendf(o, "}\n}\n");
  return o;
}

}  // namespace dbss::tools
