// Issue 13's "done when" on defective scans of known shapes
// (tests/defect_shapes.h): stray points, a hole, a half, uneven density,
// noise.  Sphere, torus and double torus, 4000 points each, two levels; each
// input is encoded once and shared between the cases (encoded()).
//
// The error of a result is the points' mean distance to its level-2
// surface, measured on the clean points (with outliers: the points before
// they were added; with a hole: the scanned part, against the complete
// scan's surface measured on the same points).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <array>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "../defect_shapes.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/point_distances.h"
#include "dbss/encoder/scan_check.h"
#include "dbss/encoder/shell_mesh.h"

using namespace dbss;
namespace dt = dbss::test;

namespace {

constexpr size_t kPoints = 4000;
constexpr uint32_t kLevels = 2;
const char* const kShapes[] = {"sphere", "torus", "double torus"};
const dt::Vec3 kHoleDirection = {0.3, 0.2, 1.0};

const dt::Shape& shape(const char* name) { return dt::genus_shape(name); }

const PointCloud& clean(const char* name) {
  static std::map<std::string, PointCloud> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    const dt::Shape& s = shape(name);
    it = cache.emplace(name, dt::sample_sdf(s.sdf, s.lo, s.hi, kPoints, 7)).first;
  }
  return it->second;
}

// The defective inputs, by variant name.
PointCloud variant(const char* name, const std::string& v) {
  const PointCloud& c = clean(name);
  if (v == "clean") return c;
  if (v == "outliers 0.5%") return dt::with_outliers(c, 0.005, 11);
  if (v == "outliers 1%") return dt::with_outliers(c, 0.01, 11);
  if (v == "hole 10%") return dt::with_hole(c, kHoleDirection, 0.10);
  if (v == "hole 15%") return dt::with_hole(c, kHoleDirection, 0.15);
  if (v == "half") return dt::half(c);
  if (v == "density 10x") return dt::with_density_gradient(c, 10.0, 13);
  if (v == "noise 0.1%") return dt::with_noise(c, 0.001, 17);
  FAIL("unknown variant " << v);
  return {};
}

const char* const kVariants[] = {"clean",    "outliers 0.5%", "outliers 1%", "hole 10%",
                                 "hole 15%", "half",          "density 10x", "noise 0.1%"};

struct Encoded {
  bool ok = false;
  std::string error;  // why encoding failed
  PointCloud input;
  Encoding e;
  TriangleMesh finest;
  MeshInfo info;
};

// The input encoded with default options, kLevels levels and `mode`; once
// per (shape, variant, mode).  Null (and a failed check naming the error)
// when encoding fails, so a case goes on with its other inputs.
const Encoded* encoded(const char* name, const std::string& v, SurfaceMode mode = SurfaceMode::automatic) {
  static std::map<std::string, Encoded> cache;
  const std::string key = std::string(name) + " / " + v + " / " + surface_mode_name(mode);
  auto it = cache.find(key);
  if (it == cache.end()) {
    Encoded r;
    r.input = variant(name, v);
    const Status valid = check_reconstructible(r.input, key);
    EncodeOptions o;
    o.levels = kLevels;
    o.control.surface = mode;
    auto e = valid.ok() ? encode_points(r.input, o) : Result<Encoding>(valid);
    if (!e.ok()) {
      r.error = e.status().to_string();
    } else if (e.value().levels.positions.size() != kLevels + 1) {
      r.error = "not " + std::to_string(kLevels) + " levels";
    } else {
      r.ok = true;
      r.e = std::move(e).value();
      r.finest = TriangleMesh{r.e.levels.positions[kLevels], r.e.levels.triangles[kLevels]};
      r.info = mesh_info(r.finest);
    }
    it = cache.emplace(key, std::move(r)).first;
  }
  if (!it->second.ok) {
    FAIL_CHECK(key << ": encoding failed: " << it->second.error);
    return nullptr;
  }
  return &it->second;
}

double error_on(const PointCloud& points, const Encoded& r) { return points_to_mesh(points.xyz, r.finest).mean; }

// The vertices on boundary edges (edges in one triangle).
std::vector<uint32_t> boundary_vertices(const TriangleMesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  for (size_t t = 0; t < m.triangle_count(); ++t)
    for (int c = 0; c < 3; ++c) {
      const uint32_t a = m.triangles[3 * t + c], b = m.triangles[3 * t + (c + 1) % 3];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  std::set<uint32_t> rim;
  for (const auto& [e, n] : edges)
    if (n == 1) rim.insert(e.first), rim.insert(e.second);
  return {rim.begin(), rim.end()};
}

double clamped_share(const Encoding& e) {
  const LevelStats& s = e.levels.stats.back();
  return s.odd ? double(s.clamped) / double(s.odd) : 0.0;
}

}  // namespace

TEST_CASE("defect shapes: the clean scans give one closed component of the right genus") {
  for (const char* name : kShapes) {
    INFO(name);
    const Encoded* rp = encoded(name, "clean");
    if (!rp) continue;
    const Encoded& r = *rp;
    CHECK(r.info.components == 1);
    CHECK(r.info.closed);
    CHECK(r.info.genus == shape(name).genus);
  }
}

TEST_CASE("defect shapes: with 1% outliers the result has the clean topology and error within 1.2x of the clean scan") {
  for (const char* name : kShapes) {
    INFO(name);
    const Encoded* cp = encoded(name, "clean");
    if (!cp) continue;
    const Encoded& c = *cp;
    const Encoded* rp = encoded(name, "outliers 1%");
    if (!rp) continue;
    const Encoded& r = *rp;
    CHECK(r.e.outliers.points_in == r.input.size());
    CHECK(r.e.outliers.kept() < r.input.size());
    CHECK(r.info.components == 1);
    CHECK(r.info.closed);
    CHECK(r.info.genus == shape(name).genus);
    const double clean_error = error_on(clean(name), c);
    const double error = error_on(clean(name), r);
    INFO("clean " << clean_error << ", with outliers " << error);
    // The bound, on every shape.  Measured: sphere 1.02x, torus
    // 1.05x, double torus 1.08x (the torus was 1.75x two sessions ago and
    // had its own bound; later sampler and outlier-pass changes brought it
    // within the issue's).
    CHECK(error <= 1.2 * clean_error);
  }
}

TEST_CASE("defect shapes: with 0.5% outliers the result has the clean topology") {
  for (const char* name : kShapes) {
    INFO(name);
    const Encoded* rp = encoded(name, "outliers 0.5%");
    if (!rp) continue;
    const Encoded& r = *rp;
    CHECK(r.info.components == 1);
    CHECK(r.info.genus == shape(name).genus);
  }
}

TEST_CASE("defect shapes: a 10% or 15% hole under closed mode keeps the genus and the error on the scanned part within 1.3x") {
  // The 15% hole cuts right through one of the double torus's tubes: the
  // two cut ends are joined by a tube, not capped (which lost a handle).
  for (const char* hole : {"hole 10%", "hole 15%"})
  for (const char* name : kShapes) {
    INFO(name << " / " << hole);
    const Encoded* cp = encoded(name, "clean");
    if (!cp) continue;
    const Encoded& c = *cp;
    const Encoded* rp = encoded(name, hole, SurfaceMode::closed);
    if (!rp) continue;
    const Encoded& r = *rp;
    CHECK_FALSE(r.e.stages.open);
    CHECK(r.info.components == 1);
    CHECK(r.info.closed);
    CHECK(r.info.genus == shape(name).genus);
    // The scanned part: the points the holed input kept.
    const double complete_error = error_on(r.input, c);
    const double error = error_on(r.input, r);
    INFO("complete scan " << complete_error << ", with the hole " << error);
    CHECK(error <= 1.3 * complete_error);
  }
}

TEST_CASE("defect shapes: a 10% or 15% hole under open mode gives a boundary along the hole") {
  for (const char* hole : {"hole 10%", "hole 15%"})
  for (const char* name : kShapes) {
    INFO(name << " / " << hole);
    const Encoded* rp = encoded(name, hole, SurfaceMode::open);
    if (!rp) continue;
    const Encoded& r = *rp;
    CHECK(r.e.stages.open);
    CHECK(r.info.components == 1);
    if (std::string(name) == "double torus" && std::string(hole) == "hole 15%") {
      // This hole runs right round one tube: its boundary is two loops, one
      // at each cut end, and that handle is gone.  Either way, each handle
      // lost is one loop more.
      CHECK((r.info.boundary_loops == 1 || r.info.boundary_loops == 2));
      CHECK(r.info.genus + r.info.boundary_loops - 1 == shape(name).genus);
    } else {
      CHECK(r.info.boundary_loops == 1);
      CHECK(r.info.genus == shape(name).genus);
      CHECK(dt::topology(r.finest).boundary_loops == 1);
    }
    // The loop runs along the hole: every boundary vertex lies within 8% of
    // the diagonal of a point the hole took out (the hole's rim, give or
    // take the cell or two the open surface's edge may recede by; measured
    // 5.1% on the torus and 6.9% on the double torus, whose 10% hole all
    // but severs one tube, leaving a ribbon whose edges are the boundary).
    // A loop elsewhere (a second opening, a flap) would be 20% or more.
    const PointCloud& c = clean(name);
    std::set<std::array<float, 3>> kept;
    for (size_t i = 0; i < r.input.size(); ++i)
      kept.insert({r.input.xyz[3 * i], r.input.xyz[3 * i + 1], r.input.xyz[3 * i + 2]});
    const PointCloud hole = dt::keep_points(
        c, [&](size_t i) { return kept.count({c.xyz[3 * i], c.xyz[3 * i + 1], c.xyz[3 * i + 2]}) == 0; });
    REQUIRE(hole.size() > 0);
    const PointIndex hole_index(hole);
    const double diagonal = dt::bounds(c).diagonal();
    const std::vector<uint32_t> rim = boundary_vertices(r.finest);
    CHECK_FALSE(rim.empty());
    double farthest = 0;
    for (uint32_t v : rim) {
      const float* p = &r.finest.positions[3 * v];
      const uint32_t q = hole_index.nearest(p);
      double d2 = 0;
      for (int a = 0; a < 3; ++a) d2 += (double{p[a]} - hole.xyz[3 * q + a]) * (double{p[a]} - hole.xyz[3 * q + a]);
      farthest = std::max(farthest, std::sqrt(d2));
    }
    INFO("boundary vertices up to " << farthest / diagonal << " of the diagonal from the hole's points");
    CHECK(farthest <= 0.08 * diagonal);
  }
}

TEST_CASE("defect shapes: a half sphere under automatic mode is open with exactly one boundary loop") {
  const Encoded* rp = encoded("sphere", "half", SurfaceMode::automatic);
  if (!rp) return;
  const Encoded& r = *rp;
  INFO(r.e.stages.surface_reason);
  CHECK(r.e.stages.open);
  CHECK(r.info.components == 1);
  CHECK_FALSE(r.info.closed);
  CHECK(r.info.boundary_loops == 1);
  CHECK(r.info.genus == 0);
  CHECK(dt::topology(r.finest).boundary_loops == 1);
}

TEST_CASE("defect shapes: a 10x density gradient keeps the genus and one component") {
  for (const char* name : kShapes) {
    INFO(name);
    const Encoded* rp = encoded(name, "density 10x");
    if (!rp) continue;
    const Encoded& r = *rp;
    CHECK(r.info.components == 1);
    CHECK(r.info.closed);
    CHECK(r.info.genus == shape(name).genus);
  }
}

TEST_CASE("defect shapes: every case is within the bounds or warned about") {
  // Within: at most 2% of the level-2 displacements clamped and the clean
  // points' mean distance to the surface at most 3 median spacings of the
  // input.  Otherwise check_scan must say so.
  for (const char* name : kShapes)
    for (const char* v : kVariants)
      for (SurfaceMode mode : {SurfaceMode::automatic, SurfaceMode::closed, SurfaceMode::open}) {
        // The forced modes only on the inputs they are meant for.
        const bool holed = std::string(v).rfind("hole", 0) == 0 || std::string(v) == "half";
        if (mode != SurfaceMode::automatic && !holed) continue;
        INFO(name << " / " << v << " / " << surface_mode_name(mode));
        const Encoded* rp = encoded(name, v, mode);
        if (!rp) continue;
        const Encoded& r = *rp;
        const PointCloud& reference = std::string(v).rfind("outliers", 0) == 0 ? clean(name) : r.input;
        const PointIndex index(r.e.points);
        const ScanCheck check = check_scan(r.e, index);
        const double spacing = dt::median_spacing(r.input);
        const double clamped = clamped_share(r.e);
        const double error = error_on(reference, r);
        std::string codes;
        for (const ScanWarning& w : check.warnings) codes += w.code + " ";
        INFO("clamped " << clamped << ", points->surface " << error << " = " << error / spacing
                        << " spacings, warnings: " << codes);
        const bool within = clamped <= 0.02 && error <= 3 * spacing;
        CHECK((within || !check.warnings.empty()));
        // The self-check's own figures agree with the encoding.
        CHECK(check.clamped_share == Approx(clamped));
        CHECK(check.open == r.e.stages.open);
        CHECK(check.surface_components == r.info.components);
      }
}

TEST_CASE("defect shapes: a handle the scan cut through is kept or the loss is warned about, never silent") {
  // A triple torus with a geodesic hole that runs round one ring: where the
  // cut end lies in the junction of two rings its loop does not face its
  // partner, the pair is capped and the genus drops.  The encoder must
  // then say so (check_scan's "topology"); where it bridges, the genus is
  // right.  Two hole directions of the hole sweep (scan_bench) that cut a
  // ring at 8,000 points.
  const dt::Shape& s = shape("triple torus");
  const PointCloud c = dt::sample_sdf(s.sdf, s.lo, s.hi, 8000, 5);
  for (const auto& [d, share] : {std::pair{dt::Vec3{0, 1, 0.3}, 0.10}, std::pair{dt::Vec3{0, 0, -1}, 0.15}}) {
    INFO("hole " << share << " towards " << d[0] << "," << d[1] << "," << d[2]);
    const PointCloud h = dt::with_hole(c, d, share);
    EncodeOptions o;
    o.levels = 1;
    o.control.surface = SurfaceMode::closed;
    auto e = encode_points(h, o);
    REQUIRE(e.ok());
    const MeshInfo i = mesh_info(TriangleMesh{e.value().levels.positions[1], e.value().levels.triangles[1]});
    const ScanCheck check = check_scan(e.value(), PointIndex(e.value().points));
    bool warned = false;
    for (const ScanWarning& w : check.warnings) warned |= w.code == "topology";
    INFO("genus " << i.genus << ", " << e.value().stages.doubtful_caps << " doubtful cap pair(s)");
    CHECK(i.components == 1);
    CHECK((i.genus == s.genus || warned));
    // Only a lost handle is warned about: a warning with the genus right
    // would be noise.
    if (i.genus == s.genus) CHECK(!warned);
  }
}

TEST_CASE("check_scan: levels past the points' density change none of its figures") {
  // Past the first level with more vertices than points every level stores
  // only zeros (dead_zone_steps): the check measures the surface there, not
  // at the finest level, whose triangles made it cost more than the levels
  // at --levels 6 (issue 15).  The same figures with and without the levels
  // after it: on the finest level the points' distance moved by 0.5% and
  // the uncovered share by 1-2%, and the clamped share read 0 whatever the
  // crossing level clamped (a level past the density samples nothing), so
  // a surface closed over a half torus lost its `clamped` warning at
  // --levels 5 that it had at 3 (review).
  const dt::Shape& s = shape("torus");
  const PointCloud pc = dt::half(dt::sample_sdf(s.sdf, s.lo, s.hi, 3000, 5));
  EncodeOptions o;
  o.levels = 5;
  o.choose_control = false;
  o.control.surface = SurfaceMode::closed;
  auto e = encode_points(pc, o);
  REQUIRE(e.ok());
  const Encoding& full = e.value();
  const PointIndex index(full.points.size() ? full.points : pc);  // (the points are kept only when outliers went)
  size_t crossing = 0;
  while (full.levels.positions[crossing].size() / 3 <= index.points().size()) ++crossing;
  INFO("first level past the points: " << crossing);
  REQUIRE(crossing + 1 < full.levels.positions.size());  // the file goes past it
  Encoding cut = full;
  cut.levels.positions.resize(crossing + 1);
  cut.levels.triangles.resize(crossing + 1);
  cut.levels.stats.resize(crossing);
  const ScanCheck a = check_scan(full, index), b = check_scan(cut, index);
  CHECK(a.surface_components == b.surface_components);
  CHECK(a.open == b.open);
  CHECK(a.uncovered_share == b.uncovered_share);
  CHECK(a.points_to_surface == b.points_to_surface);
  CHECK(a.capped_rim_pairs == b.capped_rim_pairs);
  REQUIRE(b.clamped_share > 0);  // the closed-over half clamps at the crossing level
  CHECK(a.clamped_share == b.clamped_share);
  CHECK(a.warnings.size() == b.warnings.size());
}
