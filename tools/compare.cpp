#include "compare.h"

#include <cstdio>
#include <string>

#include "dbss/measure/compare.h"
#include "dbss/encoder/point_input.h"
#include "encode_options.h"
#include "json.h"
#include "progress.h"

namespace dbss::tools {

namespace {

constexpr const char* kHelpHead =
    "usage: dbss compare INPUT [options]\n"
    "\n"
    "Encodes INPUT as dbss and measures it level by level against a full-vertex\n"
    "DSS (Loop subdivision of the same control mesh, a displacement for every\n"
    "vertex of every level, same sampler, quantizer and entropy coder) and\n"
    "against Draco on the identical dbss level mesh.  Nothing is written.\n"
    "\n"
    "  --json                 one JSON object on stdout instead of tables\n"
    "  --no-errors            skip the distance figures (much faster)\n";
constexpr const char* kHelpTail =
    "\n"
    "Columns: samples are stored displacements; dbss bytes are the file prefix\n"
    "that decodes levels 0..L; DSS bytes are header + control mesh + that level\n"
    "alone ('level') or every level so far ('all'); errors are relative to the\n"
    "bounding-box diagonal: the points' mean distance to the surface, the mean\n"
    "two-sided distance between points and surface, and the Hausdorff\n"
    "distance; clamped: displacements clamped to the sampling range, dbss/DSS.\n"
    "\n"
    "Exit status: 0 done, 1 bad input or usage, 2 internal error.\n";

std::string help() { return std::string(kHelpHead) + kEncodeOptionsHelp + kHelpTail; }

int usage(const std::string& message) {
  std::fprintf(stderr, "dbss compare: %s\n\n%s", message.c_str(), help().c_str());
  return 1;
}

std::string err(const RelativeError& e) {
  char b[64];
  std::snprintf(b, sizeof b, "%.2e %.2e %.2e", e.to_surface, e.mean, e.hausdorff);
  return b;
}

std::string err_json(const RelativeError& e) {
  char b[128];
  std::snprintf(b, sizeof b, "{\"points_to_surface\": %.6e, \"mean\": %.6e, \"hausdorff\": %.6e}", e.to_surface, e.mean,
                e.hausdorff);
  return b;
}

}  // namespace

int run_compare(const std::vector<std::string_view>& args) {
  std::string input;
  bool json = false;
  CompareOptions co;
  EncodeOptions options;
  set_command_defaults(options);  // as many levels as the points support, creases on
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string_view a = args[i];
    std::string error;
    switch (parse_encode_option(args, i, options, error)) {
      case OptionParse::ok: continue;
      case OptionParse::bad: return usage(error);
      case OptionParse::not_mine: break;
    }
    if (a == "--help" || a == "-h") {
      std::fputs(help().c_str(), stdout);
      return 0;
    } else if (a == "--json") {
      json = true;
    } else if (a == "--no-errors") {
      co.errors = false;
    } else if (!a.empty() && a[0] == '-') {
      return usage("unknown option '" + std::string(a) + "'");
    } else if (input.empty()) {
      input = a;
    } else {
      return usage("more than one input file ('" + input + "' and '" + std::string(a) + "')");
    }
  }
  if (input.empty()) return usage("no input file");
  auto points = read_points(input);
  if (!points.ok()) {
    std::fprintf(stderr, "dbss compare: %s\n", points.status().message().c_str());
    return 1;
  }
  if (Status s = check_reconstructible(points.value(), input); !s.ok()) {
    std::fprintf(stderr, "dbss compare: %s\n", s.message().c_str());
    return 1;
  }
  Progress progress("dbss compare");
  options.on_progress = [&](const std::string& what) { progress.show(what); };
  co.on_progress = options.on_progress;
  auto r = compare_representations(points.value(), options, co);
  progress.done();
  if (!r.ok()) {
    std::fprintf(stderr, "dbss compare: %s: %s\n", input.c_str(), r.status().to_string().c_str());
    return r.status().code() == ErrorCode::internal ? 2 : 1;
  }
  const Comparison& c = r.value();
  const size_t nd = co.draco_bits.size();
  if (json) {
    std::printf("{\n  \"input\": %s,\n  \"points\": %zu,\n  \"diagonal\": %.9g,\n  \"error_target\": %.6g,\n",
                json_string(input).c_str(), points.value().size(), c.encoding.diagonal, c.encoding.error);
    std::printf("  \"control\": {\"vertices\": %zu, \"triangles\": %zu, \"draco_bytes\": %zu},\n",
                c.encoding.control.vertex_count(), c.encoding.control.triangle_count(),
                c.encoding.contents.control_mesh.size());
    std::printf("  \"levels\": [\n");
    for (size_t i = 0; i < c.rows.size(); ++i) {
      const CompareRow& w = c.rows[i];
      std::printf("    {\"level\": %u, \"vertices\": %zu, \"triangles\": %zu, \"dbss_samples\": %zu, \"dss_samples\": %zu, "
                  "\"dbss_bytes\": %llu, \"dss_level_bytes\": %llu, \"dss_all_bytes\": %llu, \"dbss_clamped\": %zu, "
                  "\"dss_clamped\": %zu, \"draco\": [",
                  w.level, w.vertices, w.triangles, w.dbss_samples, w.dss_samples,
                  static_cast<unsigned long long>(w.dbss_bytes), static_cast<unsigned long long>(w.dss_level_bytes),
                  static_cast<unsigned long long>(w.dss_all_bytes), w.dbss_clamped, w.dss_clamped);
      for (size_t k = 0; k < nd; ++k) {
        std::printf("%s{\"bits\": %d, \"bytes\": %llu", k ? ", " : "", co.draco_bits[k],
                    static_cast<unsigned long long>(w.draco_bytes[k]));
        if (co.errors) std::printf(", \"error\": %s", err_json(w.draco_error[k]).c_str());
        std::printf("}");
      }
      std::printf("]");
      if (co.errors)
        std::printf(", \"dbss_error\": %s, \"dss_error\": %s", err_json(w.dbss_error).c_str(), err_json(w.dss_error).c_str());
      std::printf("}%s\n", i + 1 < c.rows.size() ? "," : "");
    }
    std::printf("  ]\n}\n");
    return 0;
  }

  std::printf("%s: %zu points, control mesh %zu vertices / %zu triangles, step %.3g (error target %.3g of the diagonal)\n\n",
              input.c_str(), points.value().size(), c.encoding.control.vertex_count(),
              c.encoding.control.triangle_count(), double(c.encoding.step), c.encoding.error);
  std::printf("%-5s %9s | %9s %9s | %9s %9s %9s", "level", "triangles", "dbss smp", "DSS smp", "dbss B", "DSS lvl B",
              "DSS all B");
  for (int b : co.draco_bits) std::printf(" %7s%-2d", "Draco", b);
  std::printf(" | %9s\n", "dbss/DSS");
  for (const CompareRow& w : c.rows) {
    std::printf("%-5u %9zu | %9zu %9zu | %9llu %9llu %9llu", w.level, w.triangles, w.dbss_samples, w.dss_samples,
                static_cast<unsigned long long>(w.dbss_bytes), static_cast<unsigned long long>(w.dss_level_bytes),
                static_cast<unsigned long long>(w.dss_all_bytes));
    for (size_t k = 0; k < nd; ++k) std::printf(" %9llu", static_cast<unsigned long long>(w.draco_bytes[k]));
    std::printf(" | %9.3f\n", double(w.dbss_bytes) / double(w.dss_all_bytes));
  }
  if (co.errors) {
    std::printf("\nerrors relative to the diagonal: points->surface mean, two-sided mean, Hausdorff\n");
    std::printf("%-5s %-26s %-26s", "level", "dbss", "DSS");
    for (int b : co.draco_bits) std::printf(" Draco %-20d", b);
    std::printf(" %s\n", "clamped dbss/DSS");
    for (const CompareRow& w : c.rows) {
      std::printf("%-5u %-26s %-26s", w.level, err(w.dbss_error).c_str(), err(w.dss_error).c_str());
      for (size_t k = 0; k < nd; ++k) std::printf(" %-26s", err(w.draco_error[k]).c_str());
      std::printf(" %zu/%zu\n", w.dbss_clamped, w.dss_clamped);
    }
  }
  return 0;
}

}  // namespace dbss::tools
