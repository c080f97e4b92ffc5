#include "dbss/encoder/encode_mesh.h"
#include "encode_steps.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>

#include "dbss/decoder/control_mesh.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/control_mesh_codec.h"
#include "dbss/encoder/control_rounding.h"
#include "dbss/encoder/hole_budget.h"
#include "dbss/encoder/quantize.h"
#include "dbss/encoder/simplify.h"
#include "dbss/format/writer.h"
#include "mesh_control_choice.h"

namespace dbss {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

std::vector<uint64_t> level_vertex_counts(uint64_t vertices, uint64_t edges, uint64_t triangles, uint32_t levels) {
  std::vector<uint64_t> r{vertices};
  for (uint32_t l = 0; l < levels; ++l) {
    vertices += edges;
    edges = 2 * edges + 3 * triangles;
    triangles *= 4;
    r.push_back(vertices);
  }
  return r;
}

uint32_t mesh_control_faces(const TriangleMesh& mesh, int64_t genus) { return hole_budget(mesh, genus).faces; }

namespace {

// The vertices of `mesh` on a boundary edge (an edge of one triangle).
std::vector<uint32_t> boundary_vertices(const TriangleMesh& mesh) {
  std::vector<uint32_t> out;
  auto topo = build_topology(static_cast<uint32_t>(mesh.vertex_count()), mesh.triangles);
  if (!topo.ok()) return out;
  const LevelTopology& t = topo.value();
  for (uint32_t h = 0; h < t.triangles.size(); ++h)
    if (t.twin[h] == kNoHalfEdge) out.push_back(t.triangles[h]), out.push_back(t.triangles[next_half(h)]);
  return out;
}

// The mesh's encoding over a control mesh of `target` faces: QEM, Draco,
// the levels cast against the input, and the file (without
// control.choice, which encode_mesh adds once the choice is made).
Status encode_over_mesh_control(const TriangleMesh& in, const MeshInfo& info, const MeshSurface& surface, uint32_t target,
                                const EncodeOptions& o, const MeshEncodeOptions& mo, Encoding& e, MeshControlStats& stats) {
  auto t = Clock::now();
  if (o.on_progress) o.on_progress("simplifying");
  auto control = control_mesh_from_mesh(in, surface, target, &stats);
  if (!control.ok()) return control.status();
  e.stages.control = std::move(control).value();
  e.stages.open = !info.closed;
  e.stages.surface_reason = "mesh input: " + std::to_string(info.components) + " component(s), genus " +
                            std::to_string(info.genus) + ", " + std::to_string(info.boundary_loops) +
                            " boundary loop(s)";
  e.stages.simplify_stats = {stats.faces_before, stats.faces_after};
  e.stages.target_faces = target;
  e.seconds.control = since(t);

  format::FileContents& c = e.contents;
  set_extent_and_step(e, in.positions, o);
  if (!(e.diagonal > 0)) return Status(ErrorCode::invalid_argument, "the mesh has no extent");
  e.control_bits = o.control_bits ? o.control_bits
                                   : control_bits_for_step(e.stages.control, static_cast<float>(e.step * mo.control_grid_steps));

  // As encode_points: everything after Draco continues from what a decoder sees.
  t = Clock::now();
  std::unique_ptr<TriangleMesh> placed;
  e.rounding = {};
  if (mo.round_along_surface) {
    placed = std::make_unique<TriangleMesh>(e.stages.control);
    // A boundary vertex takes its nearest grid point, as Draco would round
    // it: a slide in its tangent plane would move it across the rim, and
    // the rim is what BDRY and the boundary rule follow.  (Fixed inside
    // round_along_surface, whose guard against an edge's two ends on one
    // grid point then sees the rim where it ends up.)
    std::vector<uint8_t> rim(e.stages.control.vertex_count(), 0);
    for (const uint32_t v : boundary_vertices(e.stages.control)) rim[v] = 1;
    e.rounding = round_along_surface(*placed, e.control_bits, &rim);
  }
  if (Status st = control_mesh_through_draco(e, placed.get()); !st.ok()) return st;
  {
    // Every level is a 1-to-4 split of the control mesh, so it has the
    // control mesh's topology: checking the one Draco gave back (its
    // rounding may not merge or fold anything that matters) is checking
    // them all.
    const MeshInfo got = mesh_info(e.control);
    const MeshInfo& want = info;
    if (got.genus != want.genus || got.components != want.components || got.boundary_loops != want.boundary_loops)
      // Seen on inputs with parts too small to be a surface (two triangles
      // back to back): the input's doing, said as such, not an encoder bug.
      return Status(ErrorCode::invalid_argument,
                    "the control mesh lost the input's topology once its positions were rounded (genus " +
                        std::to_string(want.genus) + " -> " + std::to_string(got.genus) + ", components " +
                        std::to_string(want.components) + " -> " + std::to_string(got.components) +
                        "): the mesh may have degenerate parts (a component of two triangles back to back, or of no "
                        "area); try a larger --control-bits");
  }
  e.seconds.draco = since(t);
  e.level_count = o.levels == kAutoLevels
                      ? auto_levels({c.header.control_vertex_count, c.header.control_edge_count, c.header.control_triangle_count},
                                    in.vertex_count())
                      : o.levels;

  // Displacements cast against the input's triangles; odd vertices on a
  // boundary edge of the level being refined follow the input's boundary.
  t = Clock::now();
  std::vector<uint8_t> rim;
  std::vector<double> rim_tangent;  // per edge, 3 each: the unit direction of a boundary edge
  bool bdry_allowed = false;  // this level may carry BDRY values (MeshEncodeOptions::boundary_levels)
  bool bdry = false;          // ... and the level loop aims at them (LevelSampler::boundary_mode)
  LevelSampler sampler;
  sampler.begin_level = [&](uint32_t level, std::span<const float> positions, std::span<const uint32_t> triangles) {
    bdry_allowed = mo.boundary_values && level < 32 && (mo.boundary_levels >> level & 1u);
    bdry = bdry_allowed;
    rim.clear();
    rim_tangent.clear();
    if (!surface.has_boundary()) return;
    auto topo = build_topology(static_cast<uint32_t>(positions.size() / 3), triangles);
    if (!topo.ok()) return;
    const LevelTopology& t = topo.value();
    rim.assign(t.edge_count(), 0);
    rim_tangent.assign(3 * size_t{t.edge_count()}, 0.0);
    for (uint32_t edge = 0; edge < t.edge_count(); ++edge) {
      const uint32_t h = t.edge_half[edge];
      if (t.twin[h] != kNoHalfEdge) continue;
      rim[edge] = 1;
      const float* u = &positions[3 * size_t{t.triangles[h]}];
      const float* w = &positions[3 * size_t{t.triangles[next_half(h)]}];
      const double d[3] = {double{w[0]} - u[0], double{w[1]} - u[1], double{w[2]} - u[2]};
      const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (len > 0)
        for (int k = 0; k < 3; ++k) rim_tangent[3 * size_t{edge} + k] = d[k] / len;
    }
  };
  // With BDRY values a boundary odd vertex aims at the input's boundary
  // curve where it crosses the plane across its edge, and reaches it along
  // its normal and across the boundary; without them (a 1.2 file) it takes
  // the normal offset to the nearest boundary point, as before format 1.3.
  // (Closed input: unchanged.)
  sampler.sample = [&](uint32_t odd, const double p[3], const double n[3], double half_length) {
    const bool on_rim = odd < rim.size() && rim[odd];
    const double* tangent = on_rim && bdry ? &rim_tangent[3 * size_t{odd}] : nullptr;
    return surface.sample(p, n, half_length, on_rim, tangent);
  };
  // Format 1.3: the boundary odd vertices onto the input's boundary curve,
  // across the boundary as well as along the normal.  A closed input has
  // no boundary edge, so its file is unchanged.
  if (mo.boundary_values && surface.has_boundary())
    sampler.boundary = [&](uint32_t, const double m[3], const double b[3], const double n[3], double half_length) {
      return bdry ? surface.boundary_offset(m, b, n, half_length) : 0.0;  // 0 everywhere: no BDRY chunk
    };
  sampler.boundary_mode = [&](bool values) { bdry = values && bdry_allowed; };
  // With a level past the input's density, the levels up to it round
  // finer than the error target's step (mesh_level_step).
  const std::vector<uint64_t> vertices = level_vertex_counts(
      c.header.control_vertex_count, c.header.control_edge_count, c.header.control_triangle_count, e.level_count);
  const uint64_t finest = vertices.back(), input_vertices = in.vertex_count();
  const float target_step = e.step;
  const double ratio = mo.dense_step_ratio;
  sampler.step = [=](uint32_t, size_t odd, size_t even) {
    return mesh_level_step(target_step, odd + even, finest, input_vertices, ratio);
  };
  LevelEncodeOptions lo;
  lo.levels = e.level_count;
  lo.step = e.step;
  lo.zstd_level = o.effort;
  lo.threads = std::max(1u, o.threads);
  lo.rdo_lambda = mo.rdo_lambda;
  lo.rdo_first_level = mo.rdo_first_level;
  lo.boundary_when_pays = mo.boundary_when_pays;
  if (o.on_progress)
    lo.on_level = [&](uint32_t l) { o.on_progress("casting level " + std::to_string(l) + " of " + std::to_string(e.level_count)); };
  auto encoded = encode_levels(e.control, sampler, lo);
  if (!encoded.ok()) return encoded.status();
  e.levels = std::move(encoded).value();
  e.seconds.levels = since(t);

  t = Clock::now();
  c.header.level_count = static_cast<uint8_t>(e.level_count);
  c.header.error_target = static_cast<float>(e.error);
  c.levels = e.levels.levels;
  c.level_data = e.levels.chunks;
  c.boundary_data = e.levels.boundary_chunks;  // compressed once, when each BDRY's coding was chosen
  c.header.version_minor = format::minimum_version_minor(c);
  char error_text[32];
  std::snprintf(error_text, sizeof error_text, "%g", e.error);
  std::string params = "input=mesh control-faces=" + std::to_string(e.stages.target_faces) +
                       " control-bits=" + std::to_string(e.control_bits) + " levels=" + std::to_string(e.level_count) +
                       (o.levels == kAutoLevels ? " (auto)" : "") + " error=" + error_text +
                       " effort=" + std::to_string(o.effort);
  // Which levels rounded finer than the target's step, so the file says so.
  {
    uint32_t finer = 0;
    for (const format::Level& level : c.levels) finer += level.step < e.step;
    if (finer) {
      char ratio_text[32];
      std::snprintf(ratio_text, sizeof ratio_text, "%g", mo.dense_step_ratio);
      params += " dense-levels=" + std::to_string(finer) + " dense-step-ratio=" + ratio_text;
    }
  }
  c.metadata = {{"encoder", "dbss " + (o.encoder_version.empty() ? std::string("unknown") : o.encoder_version)},
                {"encoder.params", params}};
  if (!o.source_name.empty()) c.metadata.push_back({"source", o.source_name});
  c.metadata.push_back({"surface", e.stages.surface_reason});
  auto file = format::serialize_with_toc(c, {o.effort});
  if (!file.ok()) return file.status();
  e.bytes = std::move(file.value().bytes);
  e.toc = std::move(file.value().toc);
  e.seconds.serialize = since(t);
  return {};
}

}  // namespace

Result<MeshEncoding> encode_mesh(const TriangleMesh& mesh, const EncodeOptions& o, const MeshEncodeOptions& mo) {
  if (o.control_bits != 0 && (o.control_bits < 8 || o.control_bits > 30))
    return Status(ErrorCode::invalid_argument, "control bits must be 8..30, or 0 to derive them from the step");
  if (o.levels > format::kMaxLevelsInFormat && o.levels != kAutoLevels)
    return Status(ErrorCode::invalid_argument, "too many levels");
  if (!(mo.dense_step_ratio >= 1) || !std::isfinite(mo.dense_step_ratio))
    return Status(ErrorCode::invalid_argument, "the dense levels' step ratio must be finite and at least 1");
  MeshEncoding me;
  Encoding& e = me.encoding;
  auto t = Clock::now();
  if (o.on_progress) o.on_progress("checking the mesh");
  auto prepared = prepare_mesh_input(mesh, &me.cleanup);
  if (!prepared.ok()) return prepared.status();
  me.input = std::move(prepared).value();
  me.input_info = mesh_counts(me.input);
  const TriangleMesh& in = me.input;
  const MeshSurface surface(in);
  const double prepare_s = since(t);

  const bool choose = o.control.control_faces == 0 && o.choose_control && mo.floor_ratio > 0 && mo.larger_control > 1;
  const uint32_t target = o.control.control_faces ? o.control.control_faces : mesh_control_faces(in, me.input_info.genus);
  if (Status st = encode_over_mesh_control(in, me.input_info, surface, target, o, mo, e, me.control_stats); !st.ok()) return st;
  if (choose) {
    EncodeOptions candidate_options = o;
    if (o.on_progress) {
      const std::string prefix = "control candidate (" + std::to_string(static_cast<uint32_t>(mo.larger_control * target) & ~1u) + " faces): ";
      candidate_options.on_progress = [prefix, &o](const std::string& s) { o.on_progress(prefix + s); };
      o.on_progress("measuring the last level's floor");
    }
    const MeshControlEncoder encoder = [&](uint32_t faces, Encoding& out, MeshControlStats& stats) {
      return encode_over_mesh_control(in, me.input_info, surface, faces, candidate_options, mo, out, stats);
    };
    choose_mesh_control(e, me.control_stats, target, in, surface, encoder, {mo.floor_ratio, mo.larger_control});
    // control.choice goes into `meta`: the file is written again with it.
    const auto ts = Clock::now();
    e.contents.metadata.push_back({"control.choice", e.control_choice});
    auto file = format::serialize_with_toc(e.contents, {o.effort});
    if (!file.ok()) return file.status();
    e.bytes = std::move(file.value().bytes);
    e.toc = std::move(file.value().toc);
    e.seconds.serialize += since(ts);
  }
  e.points.xyz = in.positions;
  e.seconds.outliers = prepare_s;
  return me;
}

}  // namespace dbss
