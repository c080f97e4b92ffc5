#include "encode.h"

#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "dbss/decoder/control_mesh.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/control_mesh.h"
#include "dbss/encoder/control_mesh_codec.h"
#include "dbss/encoder/levels.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/mesh_io.h"
#include "dbss/encoder/mesh_ops.h"
#include "dbss/encoder/point_input.h"
#include "dbss/format/writer.h"

namespace dbss::tools {

namespace {

// Progress on stderr, only on a terminal and only once the work has taken
// over a second; the line is cleared when done.
class Progress {
 public:
  Progress() : start_(std::chrono::steady_clock::now()), tty_(::isatty(2) == 1) {}
  ~Progress() {
    if (shown_) std::fputs("\r\033[K", stderr);
  }
  void show(const std::string& what) {
    if (!tty_ || std::chrono::steady_clock::now() - start_ < std::chrono::seconds(1)) return;
    std::fprintf(stderr, "\r\033[Kdbss encode: %s...", what.c_str());
    std::fflush(stderr);
    shown_ = true;
  }
  void done() {
    if (shown_) std::fputs("\r\033[K", stderr);
    shown_ = false;
    tty_ = false;
  }

 private:
  std::chrono::steady_clock::time_point start_;
  bool tty_, shown_ = false;
};

constexpr const char* kHelp =
    "usage: dbss encode INPUT -o OUT.dbss [options]\n"
    "\n"
    "Reconstructs a surface from the points of INPUT (.ply, .obj, .off, .xyz,\n"
    ".stl; mesh files give their vertices) and writes it as a .dbss file.\n"
    "\n"
    "  -o, --output FILE      the .dbss to write (replaced atomically)\n"
    "  --grid N               cells along the longest side for cell carving,\n"
    "                         2..1024 (default: the finest grid the point\n"
    "                         spacing keeps closed)\n"
    "  --control-faces F      triangles of the control mesh, even, >= 4\n"
    "                         (default: an eighth of the carved shell's, at\n"
    "                         least 96 + 64 per handle, at most 4000)\n"
    "  --control-bits B       Draco position bits of the control mesh, 8..30\n"
    "                         (default 16)\n"
    "  --levels L             subdivision levels with displacements, 0..8\n"
    "                         (default 3)\n"
    "  --error E              largest quantization error of a displacement,\n"
    "                         relative to the bounding-box diagonal, 1e-7..0.1\n"
    "                         (default 1e-4: the step is 2E x diagonal)\n"
    "  --step S               quantization step in model units, instead of\n"
    "                         --error (every level)\n"
    "  --effort N             zstd level for the displacements, 1..22 (default 19)\n"
    "  --dump-stages DIR      also write every stage as an OBJ into DIR:\n"
    "                         occupied cells, carved cells, triangulated shell,\n"
    "                         shrink-wrapped, simplified, control mesh\n"
    "\n"
    "Prints per-stage times and sizes.  Exit status: 0 written, 1 bad input or\n"
    "usage, 2 internal error.\n";

bool parse_int(std::string_view s, long lo, long hi, long& out) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && out >= lo && out <= hi;
}

int usage(const std::string& message) {
  std::fprintf(stderr, "dbss encode: %s\n\n%s", message.c_str(), kHelp);
  return 1;
}

}  // namespace

int run_encode(const std::vector<std::string_view>& args) {
  std::string input, output, dump;
  long grid = 0, faces = 0, bits = 16, levels = 3, effort = 19;
  double error = 1e-4, step = 0;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string_view a = args[i];
    auto value = [&](std::string_view& v) {
      if (i + 1 >= args.size()) return false;
      v = args[++i];
      return true;
    };
    std::string_view v;
    if (a == "--help" || a == "-h") {
      std::fputs(kHelp, stdout);
      return 0;
    } else if (a == "-o" || a == "--output") {
      if (!value(v)) return usage("-o needs a file name");
      output = v;
    } else if (a == "--grid") {
      if (!value(v) || !parse_int(v, 2, 1024, grid)) return usage("--grid needs a whole number from 2 to 1024");
    } else if (a == "--control-faces") {
      if (!value(v) || !parse_int(v, 4, 1 << 24, faces) || faces % 2)
        return usage("--control-faces needs an even whole number of at least 4");
    } else if (a == "--control-bits") {
      if (!value(v) || !parse_int(v, 8, 30, bits)) return usage("--control-bits needs a whole number from 8 to 30");
    } else if (a == "--levels") {
      if (!value(v) || !parse_int(v, 0, 8, levels)) return usage("--levels needs a whole number from 0 to 8");
    } else if (a == "--effort") {
      if (!value(v) || !parse_int(v, 1, 22, effort)) return usage("--effort needs a whole number from 1 to 22");
    } else if (a == "--step") {
      if (!value(v)) return usage("--step needs a number");
      const std::string text(v);
      char* end = nullptr;
      step = std::strtod(text.c_str(), &end);
      if (end != text.c_str() + text.size() || !(step > 0 && step < 1e30)) return usage("--step needs a positive number");
    } else if (a == "--error") {
      if (!value(v)) return usage("--error needs a number");
      const std::string text(v);
      char* end = nullptr;
      error = std::strtod(text.c_str(), &end);
      if (end != text.c_str() + text.size() || !(error >= 1e-7 && error <= 0.1))
        return usage("--error needs a number from 1e-7 to 0.1");
    } else if (a == "--dump-stages") {
      if (!value(v)) return usage("--dump-stages needs a directory");
      dump = v;
    } else if (!a.empty() && a[0] == '-') {
      return usage("unknown option '" + std::string(a) + "'");
    } else if (input.empty()) {
      input = a;
    } else {
      return usage("more than one input file ('" + input + "' and '" + std::string(a) + "')");
    }
  }
  if (input.empty()) return usage("no input file");
  if (output.empty()) return usage("no output file (-o OUT.dbss)");

  using Clock = std::chrono::steady_clock;
  Progress progress;
  const auto t0 = Clock::now();
  auto points = read_points(input);
  if (!points.ok()) {
    std::fprintf(stderr, "dbss encode: %s\n", points.status().message().c_str());
    return 1;
  }
  if (Status s = check_reconstructible(points.value(), input); !s.ok()) {
    std::fprintf(stderr, "dbss encode: %s\n", s.message().c_str());
    return 1;
  }
  const double read_s = std::chrono::duration<double>(Clock::now() - t0).count();

  ControlMeshOptions options;
  options.grid = static_cast<int>(grid);
  options.control_faces = static_cast<uint32_t>(faces);
  options.on_stage = [&](const char* stage) { progress.show(stage); };
  auto stages = build_control_mesh(points.value(), options);
  if (!stages.ok()) {
    std::fprintf(stderr, "dbss encode: %s: %s\n", input.c_str(), stages.status().to_string().c_str());
    return stages.status().code() == ErrorCode::internal ? 2 : 1;
  }
  const ControlMeshStages& st = stages.value();

  // The file holds Draco's version of the control mesh; everything after
  // continues from what a decoder will see.
  const auto t1 = Clock::now();
  auto draco = encode_control_mesh(st.control, {static_cast<int>(bits), 0});
  if (!draco.ok()) {
    std::fprintf(stderr, "dbss encode: %s\n", draco.status().to_string().c_str());
    return 2;
  }
  auto decoded = decode_control_mesh(draco.value(), 1u << 30, 1u << 30);
  auto topo = decoded.ok() ? build_topology(static_cast<uint32_t>(decoded.value().vertex_count()), decoded.value().triangles)
                           : Result<LevelTopology>(decoded.status());
  if (!topo.ok()) {
    std::fprintf(stderr, "dbss encode: control mesh after Draco: %s\n", topo.status().to_string().c_str());
    return 2;
  }
  format::FileContents c;
  c.header.level_count = 0;
  c.header.control_position_bits = static_cast<uint8_t>(bits);
  c.header.control_vertex_count = static_cast<uint32_t>(decoded.value().vertex_count());
  c.header.control_edge_count = topo.value().edge_count();
  c.header.control_triangle_count = static_cast<uint32_t>(decoded.value().triangle_count());
  const PointCloud& pc = points.value();
  c.header.bbox_min = {pc.xyz[0], pc.xyz[1], pc.xyz[2]};
  c.header.bbox_max = c.header.bbox_min;
  for (size_t i = 0; i < pc.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      c.header.bbox_min[a] = std::min(c.header.bbox_min[a], pc.xyz[3 * i + a]);
      c.header.bbox_max[a] = std::max(c.header.bbox_max[a], pc.xyz[3 * i + a]);
    }
  c.control_mesh = std::move(draco).value();
  double diag2 = 0;
  for (int a = 0; a < 3; ++a) diag2 += std::pow(double(c.header.bbox_max[a]) - c.header.bbox_min[a], 2);
  const double diagonal = std::sqrt(diag2);
  const auto t2 = Clock::now();
  const PointIndex index(pc);
  LevelEncodeOptions lo;
  lo.levels = static_cast<uint32_t>(levels);
  // --step fixes the step; --error derives it from the diagonal.
  if (step > 0) error = step / (2 * diagonal);
  lo.error = error;
  lo.zstd_level = static_cast<int>(effort);
  lo.threads = 2;
  lo.on_level = [&](uint32_t l) { progress.show("sampling level " + std::to_string(l) + " of " + std::to_string(levels)); };
  auto encoded = encode_levels(decoded.value(), index, diagonal, lo);
  if (!encoded.ok()) {
    std::fprintf(stderr, "dbss encode: %s\n", encoded.status().to_string().c_str());
    return 2;
  }
  const double levels_s = std::chrono::duration<double>(Clock::now() - t2).count();
  c.header.level_count = static_cast<uint8_t>(levels);
  c.header.error_target = static_cast<float>(error);
  c.levels = encoded.value().levels;
  char error_text[32];
  std::snprintf(error_text, sizeof error_text, "%g", error);
  std::string params = "grid=" + std::to_string(st.carving.grid) + " control-faces=" +
                       std::to_string(st.control.triangle_count()) + " control-bits=" + std::to_string(bits) +
                       " levels=" + std::to_string(levels) + " error=" + error_text + " effort=" + std::to_string(effort);
  c.metadata = {{"encoder", "dbss " DBSS_VERSION}, {"encoder.params", params},
                {"source", std::filesystem::path(input).filename().string()}};
  auto bytes = format::serialize(c, {static_cast<int>(effort)});
  if (!bytes.ok()) {
    std::fprintf(stderr, "dbss encode: %s\n", bytes.status().to_string().c_str());
    return 2;
  }
  if (Status s = format::write_file_atomic(output, bytes.value()); !s.ok()) {
    std::fprintf(stderr, "dbss encode: %s\n", s.message().c_str());
    return 1;
  }
  const double write_s = std::chrono::duration<double>(Clock::now() - t1).count();

  if (!dump.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(dump, ec);
    if (ec) {
      std::fprintf(stderr, "dbss encode: %s: cannot create directory: %s\n", dump.c_str(), ec.message().c_str());
      return 1;
    }
    const std::string d = dump + "/";
    Status s;
    if (s.ok()) s = write_cells_obj(d + "1-occupied-cells.obj", st.cells, true);
    if (s.ok()) s = write_cells_obj(d + "2-carved-cells.obj", st.cells, false);
    if (s.ok()) s = write_obj(d + "3-triangulated.obj", st.shell);
    if (s.ok()) s = write_obj(d + "4-shrink-wrapped.obj", st.wrapped);
    if (s.ok()) s = write_obj(d + "5-simplified.obj", st.simplified);
    if (s.ok()) s = write_obj(d + "6-control.obj", decoded.value());
    if (!s.ok()) {
      std::fprintf(stderr, "dbss encode: %s\n", s.message().c_str());
      return 1;
    }
  }

  progress.done();
  std::printf("%s: %zu points -> %s: %zu bytes\n", input.c_str(), pc.size(), output.c_str(), bytes.value().size());
  std::printf("%-22s %9s %10s %10s  %s\n", "stage", "ms", "vertices", "triangles", "notes");
  auto row = [](const char* name, double s, const TriangleMesh* m, const std::string& notes) {
    std::printf("%-22s %9.1f %10s %10s  %s\n", name, s * 1e3, m ? std::to_string(m->vertex_count()).c_str() : "-",
                m ? std::to_string(m->triangle_count()).c_str() : "-", notes.c_str());
  };
  row("read points", read_s, nullptr, std::to_string(pc.size()) + " points");
  row("choose grid", st.seconds.grid, nullptr, "grid " + std::to_string(st.carving.grid) + (grid ? " (given)" : " (automatic)"));
  row("cell carving", st.seconds.carve, nullptr,
      std::to_string(st.carving.occupied) + " occupied, " + std::to_string(st.carving.solid) + " solid, " +
          std::to_string(st.carving.repaired) + " filled for manifoldness");
  row("triangulation", st.seconds.triangulate, &st.shell,
      std::to_string(st.shell_info.components) + " component(s), genus " + std::to_string(st.shell_info.genus));
  char wrap[128];
  std::snprintf(wrap, sizeof wrap, "%d iterations, mean distance %.3g", st.wrap_stats.iterations, st.wrap_stats.mean_distance);
  row("shrink-wrapping", st.seconds.shrink_wrap, &st.wrapped, wrap);
  row("QEM simplification", st.seconds.simplify, &st.simplified, "");
  row("projection", st.seconds.project, &st.control, std::to_string(st.projection_skipped) + " vertices kept off the points");
  row("Draco + container", write_s - levels_s, &decoded.value(), std::to_string(c.control_mesh.size()) + " bytes of Draco, " + std::to_string(bits) + "-bit positions");
  row("displacement levels", levels_s, nullptr, std::to_string(levels) + " level(s)");
  if (!dump.empty()) std::printf("stages written to %s/\n", dump.c_str());
  if (levels > 0) {
    // Quality, relative to the diagonal: the points' mean distance to each
    // level's surface, and each level's vertices' mean distance to the
    // surface of the points (a plane through their 8 nearest points).
    std::printf("\n%-5s %9s %9s %10s %11s %9s %8s %11s %11s\n", "level", "odd", "vertices", "step", "clamped", "bytes",
                "bits/odd", "pts->surf", "surf->pts");
    for (uint32_t l = 0; l <= static_cast<uint32_t>(levels); ++l) {
      PointCloud mesh_pts;
      mesh_pts.xyz = encoded.value().positions[l];
      double to_mesh = points_to_mesh(pc.xyz, {encoded.value().positions[l], encoded.value().triangles[l]}).mean;
      double to_pts = vertices_to_points_surface(mesh_pts.xyz, index).mean;
      to_mesh /= diagonal;
      to_pts /= diagonal;
      if (l == 0) {
        std::printf("%-5u %9s %9zu %10s %11s %9zu %8s %11.3e %11.3e\n", l, "-", mesh_pts.size(), "-", "-",
                    c.control_mesh.size(), "-", to_mesh, to_pts);
      } else {
        const LevelStats& ls = encoded.value().stats[l - 1];
        char clamped[32];
        std::snprintf(clamped, sizeof clamped, "%zu (%.2f%%)", ls.clamped, 100.0 * ls.clamped / std::max<size_t>(1, ls.odd));
        std::printf("%-5u %9zu %9zu %10.3g %11s %9zu %8.3f %11.3e %11.3e\n", l, ls.odd, mesh_pts.size(), ls.step, clamped,
                    ls.bytes, 8.0 * ls.bytes / std::max<size_t>(1, ls.odd), to_mesh, to_pts);
      }
    }
  }
  return 0;
}

}  // namespace dbss::tools
