#include "dbss/encoder/encode.h"
#include "control_choice.h"
#include "encode_steps.h"
#include "mesh_geometry.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "dbss/decoder/control_mesh.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/control_mesh_codec.h"
#include "dbss/encoder/control_rounding.h"
#include "dbss/encoder/mesh_info.h"
#include "dbss/encoder/open_surface.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/point_rims.h"
#include "dbss/encoder/quantize.h"
#include "dbss/encoder/surface_fit.h"
#include "dbss/encoder/tube_points.h"
#include "dbss/format/writer.h"

namespace dbss {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

uint32_t auto_levels(const format::MeshCounts& control, size_t points) {
  uint32_t l = 1;
  for (; l < format::kMaxLevelsInPractice; ++l) {
    const auto c = format::counts_at_level(control, l);
    if (!c || c->vertices > points) break;
  }
  return l;
}

void set_extent_and_step(Encoding& e, std::span<const float> xyz, const EncodeOptions& o) {
  format::Header& h = e.contents.header;
  h.bbox_min = {xyz[0], xyz[1], xyz[2]};
  h.bbox_max = h.bbox_min;
  for (size_t i = 0; i < xyz.size() / 3; ++i)
    for (int a = 0; a < 3; ++a) {
      h.bbox_min[a] = std::min(h.bbox_min[a], xyz[3 * i + a]);
      h.bbox_max[a] = std::max(h.bbox_max[a], xyz[3 * i + a]);
    }
  double diag2 = 0;
  for (int a = 0; a < 3; ++a) diag2 += std::pow(double(h.bbox_max[a]) - h.bbox_min[a], 2);
  e.diagonal = std::sqrt(diag2);
  // The quantization step, resolved here once: every level (and `dbss
  // compare`'s baseline) uses it as it is.  The error target is what the
  // header and `meta` report.
  if (o.step > 0) {
    e.step = static_cast<float>(o.step);
    e.error = o.step / (2 * e.diagonal);
  } else {
    e.step = quantization_step(o.error, e.diagonal);
    e.error = o.error;
  }
}

// `meta` quantization: on a noisy cloud the levels round at a step from the
// points' noise (levels.cpp kNoiseStep), coarser than the error target's;
// the header's error target stays the one asked for (spec: informative),
// and this says what the levels were rounded at.  Empty when every level
// has the target's step (clean clouds: their files are unchanged).
namespace {
std::string quantization_note(const Encoding& e) {
  const std::vector<format::Level>& levels = e.contents.levels;
  if (levels.empty() || e.levels.step_noise <= 0) return {};
  float lo = levels.front().step, hi = lo;
  for (const format::Level& l : levels) lo = std::min(lo, l.step), hi = std::max(hi, l.step);
  if (lo == e.step && hi == e.step) return {};
  char text[320];
  const double d = e.diagonal > 0 ? e.diagonal : 1.0;
  if (lo == hi)
    std::snprintf(text, sizeof text,
                  "levels 1-%zu rounded at step %.6g (error up to %.3g of the diagonal), not the error target's %.6g "
                  "(%.3g): a quarter of the points' noise (%.3g of the diagonal)",
                  levels.size(), double{lo}, lo / (2 * d), double{e.step}, e.error, e.levels.step_noise / d);
  else
    std::snprintf(text, sizeof text,
                  "levels 1-%zu rounded at steps %.6g to %.6g (error up to %.3g to %.3g of the diagonal), not the error "
                  "target's %.6g (%.3g): from the points' noise (%.3g of the diagonal)",
                  levels.size(), double{lo}, double{hi}, lo / (2 * d), hi / (2 * d), double{e.step}, e.error,
                  e.levels.step_noise / d);
  return text;
}
}  // namespace

Status control_mesh_through_draco(Encoding& e, const TriangleMesh* placed) {
  // The smaller of Draco's two position predictors (control_mesh_codec.h,
  // kControlDracoSpeeds): which one wins depends on the mesh and the bits.
  const TriangleMesh& mesh = placed ? *placed : e.stages.control;
  Result<std::vector<uint8_t>> draco = Status(ErrorCode::internal, "control mesh: no Draco speed");
  for (const int speed : kControlDracoSpeeds) {
    auto bytes = encode_control_mesh(mesh, {e.control_bits, speed});
    if (!bytes.ok()) return bytes.status();
    if (!draco.ok() || bytes.value().size() < draco.value().size()) draco = std::move(bytes);
  }
  auto decoded = decode_control_mesh(draco.value(), 1u << 30, 1u << 30);
  if (!decoded.ok()) return Status(ErrorCode::internal, "control mesh after Draco: " + decoded.status().to_string());
  e.control = std::move(decoded).value();
  auto topo = build_topology(static_cast<uint32_t>(e.control.vertex_count()), e.control.triangles);
  if (!topo.ok()) return Status(ErrorCode::internal, "control mesh after Draco: " + topo.status().to_string());
  format::FileContents& c = e.contents;
  c.header.control_position_bits = static_cast<uint8_t>(e.control_bits);
  c.header.control_vertex_count = static_cast<uint32_t>(e.control.vertex_count());
  c.header.control_edge_count = topo.value().edge_count();
  c.header.control_triangle_count = static_cast<uint32_t>(e.control.triangle_count());
  c.control_mesh = std::move(draco).value();
  return {};
}

namespace {

// Largest cloud the control mesh is chosen by rate-distortion for.
constexpr size_t kMaxChoicePoints = size_t{1} << 18;

// Which rule sets Draco's position bits when EncodeOptions::control_bits is 0.
enum class BitsRule { from_level0, from_step };

// Draco's position bits, unless given: from level 0's own distance to the
// points (control_bits_for_error), never finer than the step's.  Measured
// on five sampled shapes (30k points): 16 bits cost 30% more level-0 bytes
// than the step's 12-13 for no error at any level, and level 0's 10-11 a
// further 11-23% for 0-2% more error at level 0.
int control_bits(const Encoding& e, const PointIndex& index, const EncodeOptions& o, BitsRule rule) {
  if (o.control_bits) return o.control_bits;
  const TriangleMesh& control = e.stages.control;
  if (rule == BitsRule::from_step || !o.control_bits_from_level0) return control_bits_for_step(control, e.step);
  return control_bits_for_error(control, level_distance_to_points(control.positions, control.triangles, index), e.step);
}

namespace {
// Clamps the vertices of `mesh` onto the points' faces that are axis
// planes at their bounding box's sides; returns how many vertices moved.
// Why (tagged files only): Draco's grid starts at the control vertices'
// minimum and spans their largest extent, so on a machined part whose
// faces are axis planes the grid lines fall on those faces only when the
// extreme vertices lie on them.  A crease vertex snapped a little past
// such a face (the cube: 1e-5-2e-5, from the sides' fitted planes) shifts
// the whole grid, and every vertex of the faces rounds onto a line that
// far off: 0.02 of the displacement step, which every level stores as 0,
// so the offset stays in every level (bench/crease_bench.md, thirteenth
// and fifteenth sessions).  A side of the box is a face when at least
// kBoxFaceShare of the points lie on it (within kBoxFaceTolerance of the
// box's extent: a clean sample of a plane has its coordinate exactly);
// a side the points only touch along a line or a point (a cylinder's
// side, a ridge) is left alone, as is a noisy cloud's.
constexpr double kBoxFaceShare = 0.01, kBoxFaceTolerance = 1e-6;
size_t clamp_to_box_faces(TriangleMesh& mesh, const PointCloud& pc) {
  if (pc.size() == 0) return 0;
  float lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = hi[a] = pc.xyz[a];
  for (size_t i = 0; i < pc.xyz.size(); ++i) lo[i % 3] = std::min(lo[i % 3], pc.xyz[i]), hi[i % 3] = std::max(hi[i % 3], pc.xyz[i]);
  const double extent = std::max({double{hi[0]} - lo[0], double{hi[1]} - lo[1], double{hi[2]} - lo[2]});
  size_t at_lo[3] = {0, 0, 0}, at_hi[3] = {0, 0, 0};
  for (size_t i = 0; i < pc.xyz.size(); ++i) {
    at_lo[i % 3] += pc.xyz[i] - lo[i % 3] <= kBoxFaceTolerance * extent;
    at_hi[i % 3] += hi[i % 3] - pc.xyz[i] <= kBoxFaceTolerance * extent;
  }
  const double face = kBoxFaceShare * static_cast<double>(pc.size());
  size_t moved = 0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    bool any = false;
    for (int a = 0; a < 3; ++a) {
      float& x = mesh.positions[3 * v + a];
      const float c = (x < lo[a] && at_lo[a] >= face) ? lo[a] : (x > hi[a] && at_hi[a] >= face) ? hi[a] : x;
      any |= c != x;
      x = c;
    }
    moved += any;
  }
  return moved;
}
}  // namespace

// Everything after the control mesh, up to the levels: Draco's position
// bits, creases, the control mesh through Draco, the levels.  `noise`:
// point_noise(index), measured once per encoding.
Status encode_over_control(Encoding& e, const PointIndex& index, const PointNoise& noise, const EncodeOptions& o, BitsRule rule) {
  format::FileContents& c = e.contents;
  const PointCloud& pc = index.points();
  e.control_bits = control_bits(e, index, o, rule);

  // Sharp features: crease edges found from the points, their vertices
  // snapped onto the feature lines before Draco rounds them.
  auto t = Clock::now();
  format::Creases creases = find_creases(e.stages.control, index, o.creases, &e.creases);
  e.seconds.control += since(t);

  // The file holds Draco's version of the control mesh; everything after
  // continues from what a decoder will see.  Without crease tags each
  // vertex is placed on the grid point nearest its surface it can slide to
  // (control_rounding.h); the builder's mesh stays in e.stages as it was,
  // so a second pass at other bits rounds from it again.
  t = Clock::now();
  std::unique_ptr<TriangleMesh> placed;
  e.rounding = {};
  if (o.round_along_surface && creases.empty() && e.creases.snapped == 0) {
    placed = std::make_unique<TriangleMesh>(e.stages.control);
    e.rounding = round_along_surface(*placed, e.control_bits);
  } else if (!creases.empty() && o.creases.clamp_to_points) {
    placed = std::make_unique<TriangleMesh>(e.stages.control);
    e.creases.clamped_to_points = clamp_to_box_faces(*placed, pc);
  }
  if (Status st = control_mesh_through_draco(e, placed.get()); !st.ok()) return st;
  e.seconds.draco = since(t);

  // Draco renumbers: the tags follow the vertices to the decoded mesh.
  c.creases = transfer_creases(e.stages.control, creases, e.control);
  if (!c.creases.empty()) c.header.version_minor = format::kCreaseVersionMinor;
  e.level_count = o.levels == kAutoLevels
                      ? auto_levels({c.header.control_vertex_count, c.header.control_edge_count, c.header.control_triangle_count},
                                    pc.size())
                      : o.levels;
  const uint32_t level_count = e.level_count;
  t = Clock::now();
  LevelEncodeOptions lo;
  lo.levels = level_count;
  lo.step = e.step;
  lo.zstd_level = o.effort;
  lo.threads = std::max(1u, o.threads);
  lo.creases = c.creases;
  lo.wedge = o.creases.wedge;
  lo.wedge_gate = o.creases.wedge_gate;
  lo.clean_away = o.creases.clean_away;
  lo.smooth_noise = o.smooth_noise;
  if (o.on_progress)
    lo.on_level = [&](uint32_t l) {
      o.on_progress("sampling level " + std::to_string(l) + " of " + std::to_string(level_count));
    };
  auto encoded = encode_levels(e.control, index, noise, lo);
  if (!encoded.ok()) return encoded.status();
  e.levels = std::move(encoded).value();
  e.seconds.levels = since(t);

  return {};
}

// A clean cloud: neither noisy nor mildly noisy (the tight kernel's).
bool clean_cloud(const PointNoise& noise) { return noise.quiet && !noise.noisy; }

// The control mesh by rate-distortion (control_choice.h): `e` holds the
// encoding over the default face count; `coarse`, a copy of `e` taken
// before its levels, gets a quarter of those faces and its own levels, and
// replaces `e` when its curve reaches every level of e's within 2% of the
// distance to the points in no more bytes.  A quarter, not a half: the
// level that crosses the points' density then has about as many vertices
// as e's (one level later), so the coarse candidate can reach the same
// floor; with half the faces it crosses at half the vertices and its later
// levels store only zeros (armadillo: 1.25x advancing front's error, issue
// 15).  `choice` says what was kept and why, for `meta`.
Status choose_control(Encoding& e, Encoding coarse, const PointIndex& index, const PointNoise& noise, const EncodeOptions& o) {
  const auto t = Clock::now();
  const uint32_t faces = static_cast<uint32_t>(e.stages.control.triangle_count());
  const double default_work = e.seconds.control + e.seconds.draco + e.seconds.levels;
  const int64_t genus = std::max<int64_t>(0, mesh_info(e.stages.control).genus);
  uint32_t fewer = (faces / 4) & ~1u;
  // default_control_faces' own floor for the genus: fewer faces than that
  // cannot carry the handles.
  if (fewer < 96 + 64 * genus) {
    e.control_choice = std::to_string(faces) + " faces: the default (a quarter is under the floor for genus " + std::to_string(genus) + ")";
    return {};
  }
  // A default with crease edges stands.  The choice measures error against
  // the points, and next to a feature line that measure favours a coarser
  // mesh the truth does not: with creases on (40k points, crease_bench) the
  // quarter won on the fandisk at 2x the true level-3 error and on the
  // cylinder at +5%, against the rule's 2%.  Fewer faces also leave fewer
  // edges to carry the lines.
  if (e.creases.creases > 0) {
    e.control_choice = std::to_string(faces) + " faces: the default (it has " + std::to_string(e.creases.creases) +
                       " crease edges; the quarter is not compared)";
    return {};
  }
  // With a fixed level count whose last level is the one that crosses the
  // points' density, the quarter would cross it one level later, past the
  // file's end: its curve would stop short of the floor and could never
  // win, so it is not built.
  const size_t points = index.points().size();
  const auto vertices = [&e](size_t l) { return e.levels.positions[l].size() / 3; };
  const size_t last = e.levels.positions.size() - 1;
  if (o.levels != kAutoLevels && (last == 0 || (vertices(last - 1) <= points && vertices(last) > points))) {
    e.control_choice = std::to_string(faces) + " faces: the default (with " + std::to_string(last) +
                       " levels a quarter would not reach the points' density)";
    return {};
  }
  EncodeOptions oq = o;
  oq.control.control_faces = fewer;
  // The candidate is a second encoding (13-27% of the encode's time): the
  // user sees its stages and levels go by, named as the candidate's.
  oq.on_progress = nullptr;
  if (o.on_progress) {
    const std::string prefix = "control candidate (" + std::to_string(fewer) + " faces): ";
    oq.on_progress = [prefix, &o](const std::string& s) { o.on_progress(prefix + s); };
    o.on_progress(prefix + "building");
  }
  oq.control.on_stage = nullptr;
  if (oq.on_progress) oq.control.on_stage = [&oq](const char* s) { oq.on_progress(s); };
  auto stages = build_control_mesh(index, oq.control);
  // A candidate that cannot be built is no candidate: the default stands.
  if (!stages.ok()) {
    e.control_choice = std::to_string(faces) + " faces: the default (" + std::to_string(fewer) + " failed: " + stages.status().to_string() + ")";
    return {};
  }
  // Both candidates describe the same points, so they must agree on the
  // surface's topology; one that does not (a handle closed or opened, a
  // part lost, at the coarser resolution) is not the same surface for
  // fewer bytes: the default stands.
  const MeshInfo fine_info = mesh_info(e.stages.control), coarse_info = mesh_info(stages.value().control);
  if (coarse_info.genus != fine_info.genus || coarse_info.components != fine_info.components ||
      coarse_info.closed != fine_info.closed) {
    e.control_choice = std::to_string(faces) + " faces: the default (" + std::to_string(fewer) + " faces gave genus " +
                       std::to_string(coarse_info.genus) + ", " + std::to_string(coarse_info.components) +
                       " components against " + std::to_string(fine_info.genus) + ", " + std::to_string(fine_info.components) + ")";
    return {};
  }
  coarse.stages = std::move(stages).value();
  coarse.seconds.control = since(t);
  if (Status st = encode_over_control(coarse, index, noise, oq, BitsRule::from_step); !st.ok()) {
    e.control_choice = std::to_string(faces) + " faces: the default (" + std::to_string(fewer) + " failed: " + st.to_string() + ")";
    return {};
  }
  const std::vector<RdPoint> fine_curve = encoder_rd_curve(e, index), coarse_curve = encoder_rd_curve(coarse, index);
  const bool keep_coarse = keep_coarse_control(coarse_curve, fine_curve, noise.noisy, index.points().size());
  const auto describe = [](const std::vector<RdPoint>& c) {
    std::string s;
    char buf[48];
    for (const RdPoint& p : c) std::snprintf(buf, sizeof buf, "%s%.1f KB %.3g", s.empty() ? "" : ", ", p.bytes / 1000, p.error), s += buf;
    return s;
  };
  const std::string why = std::to_string(fewer) + " faces (levels: " + describe(coarse_curve) + ") against " + std::to_string(faces) +
                          " (" + describe(fine_curve) + "), distances to the points";
  if (keep_coarse) {
    // The index refers to e.points: its buffer stays with e.
    std::swap(e.points, coarse.points);
    e = std::move(coarse);
  }
  e.control_choice = (keep_coarse ? "kept " : "kept the default over ") + why;
  // The time the comparison added: the candidate that lost, and the curves.
  // Kept, the coarse candidate's own stages are in e.seconds; the default's,
  // which ran before `t`, are what it cost.
  e.seconds.choice = keep_coarse ? since(t) - (e.seconds.control + e.seconds.draco + e.seconds.levels) + default_work : since(t);
  return {};
}

// How many bits under level 0's the bits choice tries (choose_control_bits).
constexpr int kFewerControlBits = 2;

// Draco's position bits by rate-distortion, on a clean cloud whose control
// mesh was chosen (choose_control): `e` holds the kept mesh encoded with
// level 0's bits b; the same mesh is encoded with b - 1 and b - 2 up to the
// level that crosses the points' density (encoder_rd_curve's end: later
// levels store only zeros), and the fewest bits whose curve reaches every
// level of b's within 2% in no more bytes (fewest_control_bits: the face
// choice's rule, rd_curve_dominates) is kept and encoded again in full.
// The distances are means over the surface (each vertex weighted by its
// area), as the benchmark's error is.  Why: level 0's bits are chosen from
// level 0 alone, before any level is seen, and a coarser grid is often
// corrected by the levels for free.  30k clean points, seed 1
// (bench/rd_bench.md, sixteenth session): the armadillo takes 9 bits (10)
// and the knot 9 (10), their prefix at Poisson + Draco qp10's error
// 0.551 -> 0.484 and 0.768 -> 0.651 of its bytes, the armadillo's at
// advancing front + Draco qp10's 0.395 -> 0.389; the elephant keeps 11
// (at 10 and 9 its floor is 6% farther from the points; against the truth
// 9 bits put it 14% farther, fifteenth session), the eight and bunny00
// keep their quarter mesh's 10 and 9.  A finer grid is not tried: level
// 0's bits are already the step's or coarser, and more bits did not lower
// the floor (elephant at 11/13/16 bits: 1.680/1.748/1.754e-4).
// Triangles of `m` with no area (two corners on one point, or three in line).
size_t degenerate_triangles(const TriangleMesh& m) {
  size_t n = 0;
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    const mesh_geometry::V3 c = mesh_geometry::face_normal(m, f);
    n += mesh_geometry::dot(c, c) == 0;
  }
  return n;
}

Status choose_control_bits(Encoding& e, const PointIndex& index, const PointNoise& noise, const EncodeOptions& o) {
  const auto t = Clock::now();
  const std::vector<RdPoint> kept = encoder_rd_curve(e, index, true);
  const int bits = e.control_bits;
  if (kept.size() < 2 || bits <= 8) return {};
  // The candidates stop at the crossing level: the kept curve's last.
  const uint32_t levels = static_cast<uint32_t>(kept.size() - 1);
  const auto describe = [](int b, const std::vector<RdPoint>& c) {
    std::string s = std::to_string(b) + " bits (";
    char buf[48];
    for (size_t i = 0; i < c.size(); ++i) std::snprintf(buf, sizeof buf, "%s%.0f B %.4g", i ? ", " : "", c[i].bytes, c[i].error), s += buf;
    return s + ")";
  };
  std::string why = describe(bits, kept);
  std::vector<BitsCurve> candidates;
  for (int b = bits - 1; b >= std::max(8, bits - kFewerControlBits); --b) {
    EncodedLevels levels_kept = std::move(e.levels);
    Encoding c = e;
    e.levels = std::move(levels_kept);
    EncodeOptions oc = o;
    oc.control_bits = b;
    oc.levels = levels;
    oc.on_progress = nullptr;
    if (o.on_progress) {
      const std::string prefix = "control bits candidate (" + std::to_string(b) + "): ";
      oc.on_progress = [prefix, &o](const std::string& s) { o.on_progress(prefix + s); };
    }
    if (Status st = encode_over_control(c, index, noise, oc, BitsRule::from_level0); !st.ok()) break;
    // A coarser grid can round a thin triangle flat; its normal, and every
    // level's displacement directions there, would then come from rounding.
    // The distances to the points hardly see one triangle, so such a
    // candidate (and any coarser one) is not taken.
    if (degenerate_triangles(c.control) > degenerate_triangles(e.control)) {
      why += ", " + std::to_string(b) + " bits (a control triangle rounded flat)";
      break;
    }
    const std::vector<RdPoint> curve = encoder_rd_curve(c, index, true);
    why += ", " + describe(b, curve);
    candidates.push_back({b, curve});
  }
  const int best = fewest_control_bits(bits, kept, candidates);
  // The first encoding's Draco and levels, replaced below when fewer bits
  // win, were work of the choice: counted in it, as choose_control does.
  const double first = e.seconds.draco + e.seconds.levels;
  if (best != bits) {
    EncodeOptions ob = o;
    ob.control_bits = best;
    if (Status st = encode_over_control(e, index, noise, ob, BitsRule::from_level0); !st.ok()) return st;
  }
  e.control_choice += "; Draco bits " + std::to_string(best) + " of " + why + ", distances to the points over the area";
  e.seconds.choice += since(t) - (best != bits ? e.seconds.draco + e.seconds.levels - first : 0.0);
  return {};
}

// What `meta`'s surface line adds for joined tubes.
std::string tubes_joined(const TubeJoin& t) {
  if (t.tubes == 0) return "";
  char share[32];
  std::snprintf(share, sizeof share, "%.1f", 100 * t.area_share);
  return "; " + std::to_string(t.tubes) + " tube(s) the scan cut through joined across the gap (" +
         std::to_string(t.points) + " points added on the tube a bridge would follow, " + share + "% of the area)";
}

// Lost handles (issue 13): a closed surface over points that end at two
// rims facing each other across a gap (a band the scan missed right round
// a tube) must join them.  The carving caps such ends wherever the tube is
// a few cells thick (the closing shuts its open ends before any hole
// reaches the bridging stage), and the handle is lost.  Where the control
// mesh caps a pair of the points' rims (point_rims.h), the gap is sampled
// along the tube a bridge would follow (tube_points.h) and the control
// mesh built again on the points with those added.  It is kept only if it
// is still closed, has as many components, one handle more per tube and
// joins every pair it was built for; the index the rest of the encoding
// runs on is returned (null: nothing joined, `index` stands).  `joined`
// holds its points and must outlive it.
std::unique_ptr<PointIndex> join_cut_tubes(Encoding& e, const PointIndex& index, const ControlMeshOptions& co,
                                           PointCloud& joined) {
  if (e.stages.open || co.surface == SurfaceMode::open) return nullptr;
  const std::vector<PointRim> rims = find_point_rims(index);
  std::vector<std::pair<size_t, size_t>> capped;
  for (const auto& [a, b] : tube_end_pairs(rims))
    if (!surface_joins(e.stages.control, rims[a], rims[b])) capped.emplace_back(a, b);
  if (capped.empty()) return nullptr;
  // The scan's spacing as its density gives it (the side of the area each
  // point stands for: its 6th neighbour's distance times sqrt(pi / 6)), not
  // the nearest neighbour's, which on an irregular sampling is about half
  // that and gave a tube four times as dense as the scan (genus 4, two
  // components where the triple torus lost one handle).
  const double spacing = std::sqrt(std::numbers::pi / 6) * point_spacing(index, 6, 0.5);
  TubePoints tube = sample_cut_tubes(index, rims, capped, spacing);
  if (tube.tubes != capped.size()) return nullptr;
  joined = std::move(tube.points);
  auto joined_index = std::make_unique<PointIndex>(joined);
  // The second build is a control mesh's time again: the user sees its
  // stages go by, named as the join's.
  ControlMeshOptions again = co;
  if (co.on_stage) {
    const std::string prefix = "joining " + std::to_string(capped.size()) + " cut tube(s): ";
    co.on_stage(prefix.c_str());
    again.on_stage = [prefix, &co](const char* stage) { co.on_stage((prefix + stage).c_str()); };
  }
  // (The grid is searched again on the joined points: at the first build's
  // grid the hole sweep at 8,000 points joined one tube fewer, and a double
  // torus came out at 1.41x the complete scan's error instead of 1.08x.)
  auto stages = build_control_mesh(*joined_index, again);
  const auto refused = [&]() -> std::unique_ptr<PointIndex> {
    joined_index.reset();  // it refers to `joined`
    joined = PointCloud{};  // not a second copy of the cloud for the rest of the encode
    return nullptr;
  };
  if (!stages.ok() || stages.value().open) return refused();
  const TriangleMesh& control = stages.value().control;
  const MeshInfo was = mesh_info(e.stages.control), now = mesh_info(control);
  if (!now.closed || now.components != was.components || now.genus != was.genus + static_cast<int64_t>(capped.size()))
    return refused();
  for (const auto& [a, b] : capped)
    if (!surface_joins(control, rims[a], rims[b])) return refused();
  e.tubes.tubes = tube.tubes;
  e.tubes.points = tube.added;
  e.tubes.at.assign(joined.xyz.end() - static_cast<std::ptrdiff_t>(3 * tube.added), joined.xyz.end());
  e.tubes.area_share = std::min(1.0, tube.area / std::max(1e-300, mesh_area(control)));
  e.stages = std::move(stages).value();
  return joined_index;
}

}  // namespace

Result<Encoding> encode_points(const PointCloud& pc, const EncodeOptions& o) {
  if (pc.size() == 0) return Status(ErrorCode::invalid_argument, "no points");
  return encode_points(PointIndex(pc), o);
}

Result<Encoding> encode_points(const PointIndex& input_index, const EncodeOptions& o) {
  if (o.control_bits != 0 && (o.control_bits < 8 || o.control_bits > 30))
    return Status(ErrorCode::invalid_argument, "control bits must be 8..30, or 0 to derive them from the step");
  if (o.levels > format::kMaxLevelsInFormat && o.levels != kAutoLevels)
    return Status(ErrorCode::invalid_argument, "too many levels");
  if (input_index.points().size() == 0) return Status(ErrorCode::invalid_argument, "no points");
  Encoding e;
  auto t = Clock::now();
  // Outliers go before anything is built on the points; a second index only
  // when some were dropped.  `e.points` moves with `e` on return, after
  // `cleaned` (which refers to it) is gone.
  if (o.on_progress && o.outliers.enabled) o.on_progress("removing outliers");
  OutlierOptions outliers = o.outliers;
  outliers.threads = std::max(1u, o.threads);
  std::unique_ptr<PointIndex> cleaned = remove_outliers(input_index, outliers, &e.outliers, e.points);
  if (!cleaned && e.points.size() != input_index.points().size()) cleaned = std::make_unique<PointIndex>(e.points);
  const PointIndex& scan_index = cleaned ? *cleaned : input_index;
  const PointCloud& pc = scan_index.points();
  e.seconds.outliers = since(t);
  t = Clock::now();
  ControlMeshOptions co = o.control;
  if (!co.on_stage && o.on_progress) co.on_stage = [&](const char* s) { o.on_progress(s); };
  auto stages = build_control_mesh(scan_index, co);
  if (!stages.ok()) return stages.status();
  e.stages = std::move(stages).value();
  // From here the surface and its levels are built on the scan's points
  // and any added in the gaps of tubes it cut (the self-check below stays
  // on the scan's own).
  PointCloud joined;
  const std::unique_ptr<PointIndex> joined_index = join_cut_tubes(e, scan_index, co, joined);
  const PointIndex& index = joined_index ? *joined_index : scan_index;
  // How the points scatter about their surface: what every candidate's
  // levels fit by (encode_levels), measured once (its time counted here).
  const PointNoise noise = point_noise(index);
  e.noise = noise.noisy ? noise.noise : 0;
  e.noisy = noise.noisy, e.quiet = noise.quiet;
  e.seconds.control = since(t);

  // (A joined tube may reach past the scan's own box: the box bounds the surface.)
  set_extent_and_step(e, index.points().xyz, o);

  // The control mesh by rate-distortion: a candidate with a quarter of the
  // faces (choose_control) unless the face count was given.
  // Above kMaxChoicePoints the candidate's second control mesh and levels
  // cost about as much as the whole encoding again (1M points, idle 2 cores:
  // 11 of the encode's 24 s; 10M: 13 s of control mesh and 15 s of levels
  // more), for a control mesh of at most 4,000 faces.
  const bool big = pc.size() > kMaxChoicePoints;
  const bool choose = o.control.control_faces == 0 && o.choose_control && !big;
  if (o.control.control_faces == 0 && o.choose_control && big)
    e.control_choice = std::to_string(e.stages.control.triangle_count()) +
                       " faces: the default (no candidate compared over " + std::to_string(kMaxChoicePoints) + " points)";
  std::unique_ptr<Encoding> coarse;
  if (choose) coarse = std::make_unique<Encoding>(e);
  // The candidates are compared with the step's bits, as the choice was
  // measured, and the one kept is encoded again with level 0's bits.  With
  // level 0's bits on both, the bunny (30k points) kept the quarter, whose
  // floor is 2.1x the default's against the true surface (1.85e-4 against
  // 8.7e-5): the two floors are a tie against the points (0.000309 and
  // 0.000310 model units), which the rounding tipped the other way.
  // The candidates are also compared without smoothing (smooth_noise):
  // against the points, smoothed levels are farther from the points by
  // design, and with smoothing in the comparison the noisy eight kept the
  // default mesh for 30% more bytes (bench/rd_bench.md, tenth session).
  // The mesh kept is then encoded again with it.
  EncodeOptions compared = o;
  compared.smooth_noise = false;
  if (Status st = encode_over_control(e, index, noise, choose ? compared : o, choose ? BitsRule::from_step : BitsRule::from_level0); !st.ok())
    return st;
  if (choose) {
    if (Status st = choose_control(e, std::move(*coarse), index, noise, compared); !st.ok()) return st;
    coarse.reset();
    // Creases snap the control mesh in place (find_creases): a mesh with
    // them keeps the step's bits rather than being snapped twice (and
    // takes no smoothing: encode_levels).
    const bool rebits = control_bits(e, index, o, BitsRule::from_level0) != e.control_bits;
    // Smoothing acts only on a level that crosses the points' density
    // (encode_levels): a noisy file that stops before one is the same
    // without it, so it is neither encoded again nor said to be smoothed.
    const auto crosses_density = [&e, &index] {
      const std::vector<std::vector<float>>& at = e.levels.positions;
      for (size_t l = 1; l < at.size(); ++l) {
        const size_t even = at[l - 1].size() / 3, odd = at[l].size() / 3 - even;
        const double zone = dead_zone_steps(odd, index.points().size(), even);
        if (zone > 0.5 && !std::isinf(zone)) return true;
      }
      return false;
    };
    const bool smooth = o.smooth_noise && noise.noisy && crosses_density();
    if (e.creases.creases == 0 && e.creases.snapped == 0 && (rebits || smooth)) {
      const double first = e.seconds.draco + e.seconds.levels;
      if (Status st = encode_over_control(e, index, noise, o, BitsRule::from_level0); !st.ok()) return st;
      // The first pass over the kept mesh was the comparison's cost.
      e.seconds.choice += first;
      e.control_choice += "; compared with the step's control bits" + std::string(smooth ? " and unsmoothed levels" : "") +
                          ", then encoded with level 0's (" + std::to_string(e.control_bits) + ")" +
                          (smooth ? " and smoothed levels" : "");
    }
    if (clean_cloud(noise) && o.control_bits == 0 && o.control_bits_from_level0 && e.creases.creases == 0 &&
        e.creases.snapped == 0)
      if (Status st = choose_control_bits(e, index, noise, o); !st.ok()) return st;
  }
  const uint32_t level_count = e.level_count;
  format::FileContents& c = e.contents;

  // What a reader of the file should know about how far to trust it.
  t = Clock::now();
  e.check = check_scan(e, scan_index, std::max(1u, o.threads));
  e.seconds.check = since(t);

  t = Clock::now();
  c.header.level_count = static_cast<uint8_t>(level_count);
  c.header.error_target = static_cast<float>(e.error);
  c.levels = e.levels.levels;
  c.level_data = e.levels.chunks;  // compressed once, when each level's coding was chosen
  c.header.version_minor = format::minimum_version_minor(c);
  char error_text[32];
  std::snprintf(error_text, sizeof error_text, "%g", e.error);
  // The grid search may move its chosen cells by half a cell (a handle only
  // one placement shows): recorded, so --grid N --grid-shift S carves the
  // same cells again.  Left out when 0, as every file before it had it.
  char shift_text[48] = "";
  if (e.stages.carving.shift != 0) std::snprintf(shift_text, sizeof shift_text, " grid-shift=%.17g", e.stages.carving.shift);
  const std::string params = "grid=" + std::to_string(e.stages.carving.grid) + shift_text + " control-faces=" +
                             std::to_string(e.stages.target_faces) + " control-bits=" +
                             std::to_string(e.control_bits) + " levels=" + std::to_string(level_count) + (o.levels == kAutoLevels ? " (auto)" : "") +
                             " error=" + error_text + " effort=" + std::to_string(o.effort) +
                             " surface=" + surface_mode_name(o.control.surface) +
                             (o.outliers.enabled ? "" : " keep-outliers");
  c.metadata = {{"encoder", "dbss " + (o.encoder_version.empty() ? std::string("unknown") : o.encoder_version)},
                {"encoder.params", params}};
  if (!o.source_name.empty()) c.metadata.push_back({"source", o.source_name});
  c.metadata.push_back({"surface", e.stages.surface_reason + tubes_joined(e.tubes)});
  if (!e.control_choice.empty()) c.metadata.push_back({"control.choice", e.control_choice});
  if (std::string q = quantization_note(e); !q.empty()) c.metadata.push_back({"quantization", q});
  if (e.outliers.points_in != e.outliers.kept())
    c.metadata.push_back({"outliers", std::to_string(e.outliers.duplicates) + " duplicates, " +
                                          std::to_string(e.outliers.isolated) + " isolated points and " +
                                          std::to_string(e.outliers.cluster_points) + " points in " +
                                          std::to_string(e.outliers.clusters_dropped) + " small clusters dropped of " +
                                          std::to_string(e.outliers.points_in)});
  if (e.stages.bridged_area + e.tubes.area_share > 0) {
    std::snprintf(error_text, sizeof error_text, "%.4f", e.stages.bridged_area + e.tubes.area_share);
    c.metadata.push_back({"unsupported.bridged_area_share", error_text});
  }
  for (const ScanWarning& w : e.check.warnings) c.metadata.push_back({"warning." + w.code, w.message});
  auto file = format::serialize_with_toc(c, {o.effort});
  if (!file.ok()) return file.status();
  e.bytes = std::move(file.value().bytes);
  e.toc = std::move(file.value().toc);
  e.seconds.serialize = since(t);
  return e;
}

uint64_t prefix_bytes(const Encoding& e, uint32_t level) {
  // The chunk of level l is the l-th LEVL after CTRL; level 0 ends with CTRL.
  uint32_t seen = 0;
  for (const format::TocEntry& t : e.toc) {
    if (t.type == format::kCtrl && level == 0) return t.end();
    if (t.type == format::kLevl && ++seen == level) return t.end();
  }
  return e.bytes.size();
}

}  // namespace dbss
