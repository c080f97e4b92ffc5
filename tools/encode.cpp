#include "encode.h"
#include "encode_mesh.h"
#include "encode_options.h"
#include "progress.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "dbss/encoder/encode.h"
#include "dbss/encoder/mesh_shape.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/cell_dump.h"
#include "dbss/encoder/point_distances.h"
#include "dbss/encoder/point_input.h"
#include "dbss/format/writer.h"
#include "dbss/io/file.h"
#include "dbss/io/geometry_files.h"

namespace dbss::tools {

namespace {

constexpr const char* kHelpHead =
    "usage: dbss encode INPUT -o OUT.dbss [options]\n"
    "\n"
    "Encodes INPUT (.ply, .obj, .off, .xyz, .stl, .glb, .gltf) as a .dbss file.\n"
    "A file with faces is encoded as a mesh: the control mesh is simplified\n"
    "from it (genus, components and boundaries kept) and displacements are\n"
    "cast against its triangles; it must be an oriented manifold.  A point\n"
    "file (or --input points) has a surface reconstructed from its points.\n"
    "Texture coordinates, colours and normals are not carried over.\n"
    "\n"
    "  -o, --output FILE      the .dbss to write (replaced atomically)\n"
    "  --input points|mesh    read a mesh file's triangles (mesh, the default\n"
    "                         for a file with faces) or only its vertices\n"
    ;
constexpr const char* kHelpTail =
    "  --strict               fail (exit 1, nothing written) when the self-check\n"
    "                         finds the surface does not match the points\n"
    "  --no-report            skip the quality report after encoding (each\n"
    "                         level's distance to the input or the points),\n"
    "                         which costs about as much as the encoding on a\n"
    "                         large input; the file is the same\n"
    "  --dump-stages DIR      also write every stage as an OBJ into DIR:\n"
    "                         occupied cells, carved cells, triangulated shell,\n"
    "                         shrink-wrapped, simplified, control mesh\n"
    "\n"
    "Prints per-stage times and sizes, then a self-check of the result against\n"
    "the points: any figure out of bounds (components, clamped displacements,\n"
    "surface with no points near, distance to the points, outliers dropped) is\n"
    "a warning on stderr, also recorded in the file's meta chunk.\n"
    "Exit status: 0 written, 1 bad input or usage (or a warning under\n"
    "--strict), 2 internal error.\n";

std::string fmt_shift(double shift) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", shift);
  return b;
}

std::string help() { return std::string(kHelpHead) + kEncodeOptionsHelp + kHelpTail; }

int usage(const std::string& message) {
  std::fprintf(stderr, "dbss encode: %s\n\n%s", message.c_str(), help().c_str());
  return 1;
}

}  // namespace

int run_encode(const std::vector<std::string_view>& args) {
  std::string input, output, dump;
  bool strict = false, report = true;
  std::string input_mode;  // "", "points" or "mesh"
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
    } else if (a == "-o" || a == "--output") {
      if (i + 1 >= args.size()) return usage("-o needs a file name");
      output = args[++i];
    } else if (a == "--input") {
      if (i + 1 >= args.size() || (args[i + 1] != "points" && args[i + 1] != "mesh"))
        return usage("--input needs points or mesh");
      input_mode = args[++i];
    } else if (a == "--strict") {
      strict = true;
    } else if (a == "--no-report") {
      report = false;
    } else if (a == "--dump-stages") {
      if (i + 1 >= args.size()) return usage("--dump-stages needs a directory");
      dump = args[++i];
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
  if (options.control.grid_shift != 0 && options.control.grid == 0)
    return usage("--grid-shift moves a given grid's cells: it needs --grid N");

  {
    // Before the work, which can take minutes: an output that cannot be
    // written is said now, not after.
    const std::filesystem::path parent = std::filesystem::path(output).parent_path();
    std::error_code ec;
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
      std::fprintf(stderr, "dbss encode: %s: the directory %s does not exist\n", output.c_str(), parent.string().c_str());
      return 1;
    }
  }
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  Result<PointCloud> points = Status(ErrorCode::internal, "not read");
  if (input_mode != "points") {
    // A file with faces is a mesh unless told otherwise; a point file falls
    // through to reconstruction (unless --input mesh asked for faces), with
    // the points read here (a large .xyz is not parsed twice).
    auto geometry = read_geometry(input);
    if (!geometry.ok()) {
      std::fprintf(stderr, "dbss encode: %s\n", geometry.status().message().c_str());
      return 1;
    }
    if (!geometry.value().triangles.empty()) {
      if (!dump.empty()) return usage("--dump-stages is for point input (the stages of reconstruction)");
      // Reconstruction's choices mean nothing for a mesh: said, not dropped
      // in silence (the mesh path checks the topology itself, so --strict
      // has nothing more to check either).
      for (const std::string_view a : args)
        if (a == "--strict" || a == "--surface" || a == "--grid" || a == "--grid-shift" || a == "--keep-outliers" ||
            a == "--crease-angle" || a == "--no-creases")
          std::fprintf(stderr, "dbss encode: %s: note: %s is for point input; ignored for a mesh (--input points to reconstruct from its vertices)\n",
                       input.c_str(), std::string(a).c_str());
      const TriangleMesh mesh{std::move(geometry.value().points.xyz), std::move(geometry.value().triangles)};
      return run_encode_mesh(input, output, mesh, options,
                             std::chrono::duration<double>(Clock::now() - t0).count(), report);
    }
    if (input_mode == "mesh") {
      std::fprintf(stderr, "dbss encode: %s: --input mesh, but the file has no faces\n", input.c_str());
      return 1;
    }
    points = std::move(geometry.value().points);  // what read_points gives: read_geometry's points
  }
  if (!dump.empty()) {
    // Before the work (and after a mesh input refused it): a bad directory fails the command with no output written.
    std::error_code ec;
    std::filesystem::create_directories(dump, ec);
    if (ec) {
      std::fprintf(stderr, "dbss encode: %s: cannot create directory: %s\n", dump.c_str(), ec.message().c_str());
      return 1;
    }
  }
  Progress progress("dbss encode");
  if (input_mode == "points") points = read_points(input);
  if (!points.ok()) {
    std::fprintf(stderr, "dbss encode: %s\n", points.status().message().c_str());
    return 1;
  }
  if (Status s = check_reconstructible(points.value(), input); !s.ok()) {
    std::fprintf(stderr, "dbss encode: %s\n", s.message().c_str());
    return 1;
  }
  const double read_s = std::chrono::duration<double>(Clock::now() - t0).count();
  const PointCloud& pc = points.value();

  options.source_name = std::filesystem::path(input).filename().string();
  options.encoder_version = DBSS_VERSION;
  options.on_progress = [&](const std::string& what) { progress.show(what); };
  // The input's k-d tree, built here rather than inside encode_points, so
  // that the quality table below can use it again when no outlier was
  // dropped (about 6 s of one core at 10M points).
  const PointIndex input_index(pc);
  auto encoding = encode_points(input_index, options);
  progress.done();  // before any message, so none shares the progress line
  if (!encoding.ok()) {
    std::fprintf(stderr, "dbss encode: %s: %s\n", input.c_str(), encoding.status().to_string().c_str());
    return encoding.status().code() == ErrorCode::internal ? 2 : 1;
  }
  const Encoding& e = encoding.value();
  const ControlMeshStages& st = e.stages;
  for (const ScanWarning& w : e.check.warnings)
    std::fprintf(stderr, "dbss encode: %s: warning (%s): %s\n", input.c_str(), w.code.c_str(), w.message.c_str());
  if (strict && !e.check.warnings.empty()) {
    std::fprintf(stderr, "dbss encode: %s: %zu warning(s) under --strict; %s not written\n", input.c_str(),
                 e.check.warnings.size(), output.c_str());
    return 1;
  }
  if (Status s = io::write_file_atomic(output, e.bytes); !s.ok()) {
    std::fprintf(stderr, "dbss encode: %s\n", s.message().c_str());
    return 1;
  }

  if (!dump.empty()) {
    const std::string d = dump + "/";
    Status s;
    if (s.ok()) s = write_cells_obj(d + "1-occupied-cells.obj", st.cells, true);
    if (s.ok()) s = write_cells_obj(d + "2-carved-cells.obj", st.cells, false);
    if (s.ok()) s = write_mesh(d + "3-triangulated.obj", st.shell);
    if (s.ok()) s = write_mesh(d + "4-shrink-wrapped.obj", st.wrapped);
    if (s.ok()) s = write_mesh(d + "5-simplified.obj", st.simplified);
    if (s.ok()) s = write_mesh(d + "6-control.obj", e.control);
    if (!s.ok()) {
      std::fprintf(stderr, "dbss encode: %s\n", s.message().c_str());
      return 1;
    }
  }

  std::printf("%s: %zu points -> %s: %zu bytes\n", input.c_str(), pc.size(), output.c_str(), e.bytes.size());
  std::printf("%-22s %9s %10s %10s  %s\n", "stage", "ms", "vertices", "triangles", "notes");
  auto row = [](const char* name, double s, const TriangleMesh* m, const std::string& notes) {
    std::printf("%-22s %9.1f %10s %10s  %s\n", name, s * 1e3, m ? std::to_string(m->vertex_count()).c_str() : "-",
                m ? std::to_string(m->triangle_count()).c_str() : "-", notes.c_str());
  };
  row("read points", read_s, nullptr, std::to_string(pc.size()) + " points");
  if (options.outliers.enabled)
    row("outliers", e.seconds.outliers, nullptr,
        (e.outliers.duplicates ? std::to_string(e.outliers.duplicates) + " duplicates merged, " : std::string()) +
            std::to_string(e.outliers.isolated) + " isolated points dropped, " + std::to_string(e.outliers.cluster_points) +
            " in " + std::to_string(e.outliers.clusters_dropped) + " small cluster(s) of " + std::to_string(e.outliers.clusters));
  row("choose grid", st.seconds.grid, nullptr,
      "grid " + std::to_string(st.carving.grid) + (st.carving.shift != 0 ? ", moved " + fmt_shift(st.carving.shift) + " cell" : "") +
          (options.control.grid ? " (given)" : " (automatic)"));
  row("cell carving", st.seconds.carve, nullptr,
      std::to_string(st.carving.occupied) + " occupied, " + std::to_string(st.carving.solid) + " solid, " +
          std::to_string(st.carving.repaired) + " filled for manifoldness" +
          (options.control.grid ? "" : " (carved by the grid search)"));
  row("triangulation", st.seconds.triangulate, &st.shell,
      std::to_string(st.shell_info.components) + " component(s), genus " + std::to_string(st.shell_info.genus));
  char wrap[192];
  std::snprintf(wrap, sizeof wrap, "%d iterations, mean distance %.3g", st.wrap_stats.iterations, st.wrap_stats.mean_distance);
  std::string wrap_notes = wrap;
  if (st.wrap_stats.untangled) wrap_notes += ", " + std::to_string(st.wrap_stats.untangled) + " folded edges smoothed";
  if (st.wrap_stats.undone) wrap_notes += ", " + std::to_string(st.wrap_stats.undone) + " moves undone (triangles crossed)";
  row("shrink-wrapping", st.seconds.shrink_wrap, &st.wrapped, wrap_notes);
  std::string surface_notes = st.surface_reason;
  if (st.cut_triangles) surface_notes += " (" + std::to_string(st.cut_triangles) + " shell triangles cut away" +
                                         (st.pinholes ? ", " + std::to_string(st.pinholes) + " pinholes closed" : "") + ")";
  row("surface", 0, nullptr, surface_notes);
  row("QEM simplification", st.seconds.simplify, &st.simplified, "");
  {
    // Before: QEM's mesh; after: the control mesh in the file (shaped,
    // projected, Draco-quantized).
    const ShapeStats& sh = st.shape_stats;
    const MeshShape final_shape = mesh_shape(e.control);
    char notes[224];
    std::snprintf(notes, sizeof notes,
                  "%zu flips, %zu moves; triangles under quality %.1f: QEM's %.1f%%, the control mesh's %.1f%%; max valence %u, %u",
                  sh.flips, sh.moves, kPoorQuality, 100 * sh.before.poor_share, 100 * final_shape.poor_share,
                  sh.before.max_valence, final_shape.max_valence);
    row("shaping", st.seconds.shape, &st.control, options.control.shape.enabled ? notes : "off");
  }
  row("projection", st.seconds.project, &st.control, std::to_string(st.projection_skipped) + " vertices kept off the points");
  row("Draco", e.seconds.draco, &e.control, std::to_string(e.contents.control_mesh.size()) + " bytes of Draco, " + std::to_string(e.control_bits) + "-bit positions");
  // Under auto the count stops at the first level denser than the points,
  // unless the level limit came first.
  std::string levels_note = std::to_string(e.level_count) + " level(s)";
  if (options.levels == kAutoLevels)
    levels_note += e.levels.positions.back().size() / 3 > e.points.size()
                       ? " (auto: level " + std::to_string(e.level_count) + " is the first with more vertices than the " +
                             std::to_string(e.points.size()) + " points)"
                       : " (auto: the most levels --levels allows)";
  row("displacement levels", e.seconds.levels, nullptr, levels_note);
  row("self-check", e.seconds.check, nullptr, std::to_string(e.check.warnings.size()) + " warning(s)");
  row("container", e.seconds.serialize, nullptr, std::to_string(e.bytes.size()) + " bytes");
  if (!dump.empty()) std::printf("stages written to %s/\n", dump.c_str());
  if (e.level_count > 0) {
    // Quality, relative to the diagonal: the points' mean distance to each
    // level's surface, and each level's vertices' mean distance to the
    // surface of the points (a plane through their 8 nearest points).
    // Against the points the surface was built from (outliers dropped):
    // the input's own index when they are the input.
    std::unique_ptr<PointIndex> cleaned_index;
    if (report && e.points.size() != pc.size()) cleaned_index = std::make_unique<PointIndex>(e.points);
    const PointIndex& index = cleaned_index ? *cleaned_index : input_index;
    // The points' distance over at most 2^18 of them evenly spaced in input
    // order, as the self-check measures it: over all of 10M points, each
    // level took longer than the encoding.
    std::vector<float> sampled;
    const size_t n = e.points.size(), m = std::min<size_t>(n, size_t{1} << 18);
    if (report && m < n)
      for (size_t s = 0; s < m; ++s) sampled.insert(sampled.end(), &e.points.xyz[3 * (s * n / m)], &e.points.xyz[3 * (s * n / m) + 3]);
    const std::vector<float>& report_points = m < n ? sampled : e.points.xyz;
    std::printf("\n%-5s %9s %9s %10s %11s %9s %8s %11s %11s\n", "level", "odd", "vertices", "step", "clamped", "bytes",
                "bits/odd", "pts->surf", "surf->pts");
    for (uint32_t l = 0; l <= e.level_count; ++l) {
      PointCloud mesh_pts;
      mesh_pts.xyz = e.levels.positions[l];
      // --no-report: the sizes cost nothing and stay; the distances, as
      // costly as the encoding on a large input, print '-'.
      char to_mesh[16] = "-", to_pts[16] = "-";
      if (report) {
        std::snprintf(to_mesh, sizeof to_mesh, "%.3e",
                      points_to_mesh(report_points, {e.levels.positions[l], e.levels.triangles[l]}).mean / e.diagonal);
        std::snprintf(to_pts, sizeof to_pts, "%.3e", vertices_to_points_surface(mesh_pts.xyz, index).mean / e.diagonal);
      }
      if (l == 0) {
        std::printf("%-5u %9s %9zu %10s %11s %9zu %8s %11s %11s\n", l, "-", mesh_pts.size(), "-", "-",
                    e.contents.control_mesh.size(), "-", to_mesh, to_pts);
      } else {
        const LevelStats& ls = e.levels.stats[l - 1];
        char clamped[32];
        std::snprintf(clamped, sizeof clamped, "%zu (%.2f%%)", ls.clamped, 100.0 * ls.clamped / std::max<size_t>(1, ls.odd));
        std::printf("%-5u %9zu %9zu %10.3g %11s %9zu %8.3f %11s %11s\n", l, ls.odd, mesh_pts.size(), ls.step, clamped,
                    ls.bytes, 8.0 * ls.bytes / std::max<size_t>(1, ls.odd), to_mesh, to_pts);
      }
    }
  }
  const ScanCheck& c = e.check;
  char figures[256];
  std::snprintf(figures, sizeof figures,
                "%u component(s) for %u point cluster(s), %s%s%.2f%% clamped, %.2f%% of the surface without points near, "
                "points %.2f spacings from the surface",
                c.surface_components, c.point_clusters, c.open ? "open, " : "closed",
                c.open ? (std::to_string(c.boundary_loops) + " boundary loop(s), ").c_str() : ", ", 100 * c.clamped_share,
                100 * c.uncovered_share, c.spacing > 0 ? c.points_to_surface / c.spacing : 0.0);
  // On noise the clamped share is a coarser level's than the table's last
  // (check_scan: past the noise, the noise alone clamps); say which.
  const bool coarser = !e.levels.stats.empty() && c.clamped_level != e.levels.stats.back().level && e.noise > 0;
  const std::string clamped_at =
      coarser ? " (clamped share of level " + std::to_string(c.clamped_level) + ", the finest whose half edge is over the points' noise)" : "";
  std::printf("\nself-check: %s: %s%s\n", c.warnings.empty() ? "ok" : (std::to_string(c.warnings.size()) + " warning(s)").c_str(),
              figures, clamped_at.c_str());
  return 0;
}

}  // namespace dbss::tools
