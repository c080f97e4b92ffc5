// dbss.encode / dbss.encode_file: the C++ encoder (encode_points) with its
// options read by the command's own parser (tools/encode_options.h), so a
// keyword means exactly what the flag of `dbss encode` means.
#include "encode.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <pybind11/numpy.h>

#include "dbss/encoder/mesh_shape.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/encode_mesh.h"
#include "dbss/encoder/point_input.h"
#include "dbss/io/file.h"
#include "dbss/io/geometry_files.h"
#include "encode_options.h"
#include "errors.h"

namespace dbss::python {

namespace py = pybind11;

namespace {

struct Settings {
  EncodeOptions options;
  bool strict = false;
  std::string input;  // "", "points" or "mesh": as `dbss encode --input`
};

// Keyword arguments as `dbss encode` flags: levels=2 is --levels 2,
// control_faces=200 is --control-faces 200, keep_outliers=True is
// --keep-outliers, crease_angle="off" is --crease-angle off.  None leaves
// the default.
Settings settings_from(const py::dict& kwargs, const char* fn) {
  Settings s;
  tools::set_command_defaults(s.options);  // the command's defaults: levels auto, creases on
  s.options.encoder_version = DBSS_VERSION;
  static const std::vector<std::string> flags = {"levels", "error", "step", "grid", "grid_shift", "control_faces",
                                                 "control_bits", "effort", "surface", "crease_angle"};
  std::vector<std::string> args, keys;
  for (auto item : kwargs) {
    const std::string key = py::str(item.first);
    const py::handle v = item.second;
    if (v.is_none()) continue;
    if (key == "keep_outliers") {
      if (v.cast<bool>()) args.push_back("--keep-outliers"), keys.push_back(key);
    } else if (key == "strict") {
      s.strict = v.cast<bool>();
    } else if (key == "input") {
      s.input = v.cast<std::string>();
      if (s.input != "points" && s.input != "mesh")
        throw py::value_error(std::string(fn) + "(): input needs \"points\" or \"mesh\"");
    } else if (key == "source_name") {
      s.options.source_name = v.cast<std::string>();
    } else if (key == "threads") {
      const int n = v.cast<int>();
      if (n < 1 || n > 1024) throw py::value_error(std::string(fn) + "(): threads needs a whole number from 1 to 1024");
      s.options.threads = static_cast<unsigned>(n);
    } else if (std::find(flags.begin(), flags.end(), key) != flags.end()) {
      if (py::isinstance<py::bool_>(v))
        throw py::type_error(std::string(fn) + "(): " + key + " takes a number or a word, not a bool");
      std::string flag = "--" + key;
      std::replace(flag.begin(), flag.end(), '_', '-');
      args.push_back(flag), keys.push_back(key);
      args.push_back(py::str(v)), keys.push_back(key);  // str(float) round-trips
    } else {
      throw py::type_error(std::string(fn) + "() got an unexpected keyword argument '" + key + "'");
    }
  }
  const std::vector<std::string_view> views(args.begin(), args.end());
  for (size_t i = 0; i < views.size(); ++i) {
    std::string error;
    const size_t at = i;
    if (tools::parse_encode_option(views, i, s.options, error) != tools::OptionParse::ok)
      throw py::value_error(std::string(fn) + "(): " + keys[at] + "=" + (at + 1 < args.size() ? args[at + 1] : "") +
                            ": " + error);
  }
  if (s.options.control.grid_shift != 0 && s.options.control.grid == 0)
    throw py::value_error(std::string(fn) + "(): grid_shift moves a given grid's cells: it needs grid");
  return s;
}

py::dict mesh_counts(double seconds, const TriangleMesh* m) {
  py::dict d;
  d["seconds"] = seconds;
  if (m) {
    d["vertices"] = m->vertex_count();
    d["triangles"] = m->triangle_count();
  }
  return d;
}

// Per stage and per level, the figures `dbss encode` prints.
py::dict stats_dict(const Encoding& e, size_t points_in, const EncodeOptions& o) {
  const ControlMeshStages& st = e.stages;
  py::dict stages;
  py::dict outliers = mesh_counts(e.seconds.outliers, nullptr);
  outliers["enabled"] = o.outliers.enabled;
  outliers["duplicates"] = e.outliers.duplicates;
  outliers["isolated"] = e.outliers.isolated;
  outliers["clusters"] = e.outliers.clusters;
  outliers["clusters_dropped"] = e.outliers.clusters_dropped;
  outliers["cluster_points"] = e.outliers.cluster_points;
  stages["outliers"] = outliers;
  py::dict grid = mesh_counts(st.seconds.grid, nullptr);
  grid["cpu_seconds"] = st.cpu_seconds.grid;
  grid["grid"] = st.carving.grid;
  grid["given"] = o.control.grid != 0;
  grid["shift"] = st.carving.shift;
  stages["choose_grid"] = grid;
  py::dict carve = mesh_counts(st.seconds.carve, nullptr);
  carve["cpu_seconds"] = st.cpu_seconds.carve;
  carve["occupied"] = st.carving.occupied;
  carve["solid"] = st.carving.solid;
  carve["repaired"] = st.carving.repaired;
  stages["cell_carving"] = carve;
  py::dict tri = mesh_counts(st.seconds.triangulate, &st.shell);
  tri["cpu_seconds"] = st.cpu_seconds.triangulate;
  tri["components"] = st.shell_info.components;
  tri["genus"] = st.shell_info.genus;
  stages["triangulation"] = tri;
  py::dict wrap = mesh_counts(st.seconds.shrink_wrap, &st.wrapped);
  wrap["cpu_seconds"] = st.cpu_seconds.shrink_wrap;
  wrap["iterations"] = st.wrap_stats.iterations;
  wrap["mean_distance"] = st.wrap_stats.mean_distance;
  wrap["untangled"] = st.wrap_stats.untangled;
  wrap["undone"] = st.wrap_stats.undone;
  stages["shrink_wrapping"] = wrap;
  py::dict surface;
  surface["open"] = st.open;
  surface["reason"] = st.surface_reason;
  surface["cut_triangles"] = st.cut_triangles;
  surface["bridged_area_share"] = st.bridged_area;
  surface["doubtful_caps"] = st.doubtful_caps;
  stages["surface"] = surface;
  py::dict simplification = mesh_counts(st.seconds.simplify, &st.simplified);
  simplification["cpu_seconds"] = st.cpu_seconds.simplify;
  stages["simplification"] = simplification;
  // The shaping pass: QEM's mesh before, the control mesh in the file after
  // (as `dbss encode`'s "shaping" row reports them).
  py::dict shape = mesh_counts(st.seconds.shape, &st.control);
  shape["cpu_seconds"] = st.cpu_seconds.shape;
  const MeshShape final_shape = mesh_shape(e.control);
  shape["enabled"] = o.control.shape.enabled;
  shape["flips"] = st.shape_stats.flips;
  shape["moves"] = st.shape_stats.moves;
  shape["poor_share_before"] = st.shape_stats.before.poor_share;
  shape["poor_share_after"] = final_shape.poor_share;
  shape["max_valence_before"] = st.shape_stats.before.max_valence;
  shape["max_valence_after"] = final_shape.max_valence;
  stages["shaping"] = shape;
  py::dict project = mesh_counts(st.seconds.project, &st.control);
  project["cpu_seconds"] = st.cpu_seconds.project;
  project["kept_off"] = st.projection_skipped;
  stages["projection"] = project;
  py::dict draco = mesh_counts(e.seconds.draco, &e.control);
  draco["bytes"] = e.contents.control_mesh.size();
  draco["position_bits"] = e.control_bits;
  stages["draco"] = draco;
  stages["levels"] = mesh_counts(e.seconds.levels, nullptr);
  py::dict check = mesh_counts(e.seconds.check, nullptr);
  check["surface_components"] = e.check.surface_components;
  check["point_clusters"] = e.check.point_clusters;
  check["open"] = e.check.open;
  check["boundary_loops"] = e.check.boundary_loops;
  check["clamped_share"] = e.check.clamped_share;
  check["clamped_level"] = e.check.clamped_level;  // the level clamped_share is of (coarser than the finest on noise)
  check["uncovered_share"] = e.check.uncovered_share;
  check["points_to_surface"] = e.check.points_to_surface;
  check["spacing"] = e.check.spacing;
  stages["self_check"] = check;
  py::dict container = mesh_counts(e.seconds.serialize, nullptr);
  container["bytes"] = e.bytes.size();
  stages["container"] = container;

  py::list levels;
  py::dict l0;
  l0["level"] = 0;
  l0["vertices"] = e.levels.positions.empty() ? e.control.vertex_count() : e.levels.positions[0].size() / 3;
  l0["bytes"] = e.contents.control_mesh.size();
  levels.append(l0);
  for (const LevelStats& ls : e.levels.stats) {
    py::dict d;
    d["level"] = ls.level;
    d["odd"] = ls.odd;
    d["vertices"] = ls.level < e.levels.positions.size() ? e.levels.positions[ls.level].size() / 3 : 0;
    d["step"] = ls.step;
    d["clamped"] = ls.clamped;
    d["bytes"] = ls.bytes;
    d["bits_per_odd"] = 8.0 * static_cast<double>(ls.bytes) / static_cast<double>(std::max<size_t>(1, ls.odd));
    d["coding"] = format::coding_name(ls.coding);
    levels.append(d);
  }
  py::list warnings;
  for (const ScanWarning& w : e.check.warnings) {
    py::dict d;
    d["code"] = w.code;
    d["message"] = w.message;
    warnings.append(d);
  }
  py::dict out;
  out["points"] = points_in;
  out["points_used"] = e.points.size();
  out["bytes"] = e.bytes.size();
  out["level_count"] = e.level_count;
  out["step"] = e.step;
  out["error"] = e.error;
  out["diagonal"] = e.diagonal;
  out["stages"] = stages;
  out["levels"] = levels;
  out["warnings"] = warnings;
  return out;
}

// Runs the encoder without the GIL.  `name` names the points in messages.
Encoding run(const PointCloud& pc, const Settings& s, const std::string& name) {
  Result<Encoding> r = Status();
  Status unusable;  // its message names the points already
  {
    py::gil_scoped_release nogil;
    unusable = check_reconstructible(pc, name);
    if (unusable.ok()) r = encode_points(pc, s.options);
  }
  if (!unusable.ok()) throw_status(unusable);
  if (!r.ok()) {
    const Status st = r.status();
    throw_status(Status(st.code(), name + ": " + st.message(), st.offset()));
  }
  Encoding& e = r.value();
  if (s.strict && !e.check.warnings.empty()) {
    std::string codes;
    for (const ScanWarning& w : e.check.warnings) codes += (codes.empty() ? "" : ", ") + w.code + ": " + w.message;
    throw_status(Status(ErrorCode::invalid_argument, name + ": " + std::to_string(e.check.warnings.size()) +
                                                         " warning(s) under strict=True: " + codes));
  }
  return std::move(r).value();
}

// Runs the mesh encoder (dbss encode on a file with faces) without the
// GIL; the input's topology goes to `input` for the statistics.
Encoding run_mesh(const TriangleMesh& mesh, const Settings& s, const std::string& name, MeshInfo& input) {
  Result<MeshEncoding> r = Status();
  {
    py::gil_scoped_release nogil;
    r = encode_mesh(mesh, s.options);
  }
  if (!r.ok()) {
    const Status st = r.status();
    throw_status(Status(st.code(), name + ": " + st.message(), st.offset()));
  }
  input = r.value().input_info;
  return std::move(r.value().encoding);
}

py::dict mesh_stats(const Encoding& e, size_t vertices, const Settings& s, const MeshInfo& input) {
  py::dict d = stats_dict(e, vertices, s.options);
  py::dict in;
  in["components"] = input.components;
  in["genus"] = input.genus;
  in["boundary_loops"] = input.boundary_loops;
  d["input"] = "mesh";
  d["mesh"] = in;
  return d;
}

}  // namespace

void register_encode(py::module_& m) {
  m.def("check_options", [](py::dict kwargs) { settings_from(kwargs, "encode"); }, py::arg("options"));
  m.def(
      "encode",
      [](py::array_t<float, py::array::c_style | py::array::forcecast> points, py::dict kwargs, bool with_stats,
         py::object faces) {
        const Settings s = settings_from(kwargs, "encode");
        if (points.ndim() != 2 || points.shape(1) != 3)
          throw py::value_error("encode(): points must be an N x 3 array");
        PointCloud pc;
        pc.xyz.assign(points.data(), points.data() + points.size());
        for (size_t i = 0; i < pc.xyz.size(); ++i)
          if (!std::isfinite(pc.xyz[i]))
            throw py::value_error("encode(): point " + std::to_string(i / 3) + " is not finite (NaN or infinite)");
        if (!faces.is_none() && s.input != "points") {
          // A (vertices, faces) mesh, encoded as `dbss encode` encodes a
          // mesh file: its own QEM control mesh, displacements cast.
          const auto f = faces.cast<py::array_t<int64_t, py::array::c_style | py::array::forcecast>>();
          if (f.ndim() != 2 || f.shape(1) != 3) throw py::value_error("encode(): faces must be an F x 3 array");
          TriangleMesh mesh{pc.xyz, {}};
          mesh.triangles.reserve(static_cast<size_t>(f.size()));
          const size_t nv = pc.size();
          for (py::ssize_t i = 0; i < f.size(); ++i) {
            const int64_t v = f.data()[i];
            if (v < 0 || static_cast<uint64_t>(v) >= nv)
              throw py::value_error("encode(): face " + std::to_string(i / 3) + " names vertex " + std::to_string(v) +
                                    "; there are " + std::to_string(nv));
            mesh.triangles.push_back(static_cast<uint32_t>(v));
          }
          MeshInfo input;
          const Encoding e = run_mesh(mesh, s, "mesh", input);
          py::bytes data(reinterpret_cast<const char*>(e.bytes.data()), e.bytes.size());
          if (!with_stats) return py::object(data);
          return py::object(py::make_tuple(data, mesh_stats(e, nv, s, input)));
        }
        if (s.input == "mesh") throw py::value_error("encode(): input=\"mesh\" needs (vertices, faces)");
        const Encoding e = run(pc, s, "points");
        py::bytes data(reinterpret_cast<const char*>(e.bytes.data()), e.bytes.size());
        if (!with_stats) return py::object(data);
        return py::object(py::make_tuple(data, stats_dict(e, pc.size(), s.options)));
      },
      py::arg("points"), py::arg("options"), py::arg("with_stats"), py::arg("faces") = py::none());
  m.def(
      "encode_file",
      [](const std::string& path, const std::string& out_path, py::dict kwargs) {
        Settings s = settings_from(kwargs, "encode_file");
        if (s.options.source_name.empty()) s.options.source_name = std::filesystem::path(path).filename().string();
        if (s.input != "points") {
          // As the command: a file with faces is a mesh unless input="points".
          Result<GeometryFile> g = Status();
          {
            py::gil_scoped_release nogil;
            g = read_geometry(path);
          }
          if (!g.ok()) throw_status(g.status());
          if (!g.value().triangles.empty()) {
            const TriangleMesh mesh{std::move(g.value().points.xyz), std::move(g.value().triangles)};
            MeshInfo input;
            const Encoding e = run_mesh(mesh, s, path, input);
            Status written;
            {
              py::gil_scoped_release nogil;
              written = io::write_file_atomic(out_path, e.bytes);
            }
            if (!written.ok()) throw_status(written);
            return mesh_stats(e, mesh.vertex_count(), s, input);
          }
          if (s.input == "mesh") throw_status(Status(ErrorCode::invalid_argument, path + ": input=\"mesh\", but the file has no faces"));
        }
        Result<PointCloud> pc = Status();
        {
          py::gil_scoped_release nogil;
          pc = read_points(path);
        }
        if (!pc.ok()) throw_status(pc.status());
        const Encoding e = run(pc.value(), s, path);
        Status written;
        {
          py::gil_scoped_release nogil;
          written = io::write_file_atomic(out_path, e.bytes);
        }
        if (!written.ok()) throw_status(written);
        return stats_dict(e, pc.value().size(), s.options);
      },
      py::arg("path"), py::arg("out_path"), py::arg("options"));
}

}  // namespace dbss::python
