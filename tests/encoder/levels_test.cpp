#include <catch2/catch.hpp>

#include <cmath>
#include <iterator>
#include <string>
#include <utility>

#include "../sampled_shapes.h"
#include "dbss/decoder/control_mesh.h"
#include "dbss/decoder/progressive.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/control_mesh.h"
#include "dbss/encoder/control_mesh_codec.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/levels.h"
#include "dbss/measure/surface_distance.h"
#include "dbss/encoder/point_distances.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/triangle_tree.h"
#include "dbss/format/reader.h"
#include "dbss/format/writer.h"

using namespace dbss;


namespace {

// What the encoder achieves today on the test shapes, relative to the
// bounding-box diagonal, per level 0..3; the tests allow twice these (a
// regression by 2x fails; the margin covers small changes of the control
// mesh).  A failing check prints the value it measured.
struct Measured {
  const char* name;
  double value[4];
};
double measured(const Measured* table, size_t n, const char* name, uint32_t level) {
  for (size_t i = 0; i < n; ++i)
    if (std::string(table[i].name) == name) return table[i].value[level];
  FAIL("no measurement for " << name);
  return 0;
}

// Closed loop, 30,000 points, error 1e-4: the vertices' mean |sdf| (how far
// they sit off the true surface).
constexpr Measured kVertexOffset[] = {
    {"torus", {4.0e-6, 1.43e-4, 1.24e-4, 1.14e-4}},
    {"double torus", {2.0e-6, 3.56e-4, 3.14e-4, 2.86e-4}},
};
// Closed loop: the points' mean distance to level 3.
constexpr Measured kClosedLoopLevel3[] = {
    {"torus", {0, 0, 0, 5.81e-5}},
    {"double torus", {0, 0, 0, 9.11e-5}},
};
// encode_points with 20,000 points and the default options: the points'
// mean distance to each level (exact point-to-triangle).
constexpr Measured kPointsToSurface[] = {
    {"sphere", {9.23e-4, 3.24e-4, 1.31e-4, 5.86e-5}},
    {"torus", {1.07e-3, 4.68e-4, 2.00e-4, 8.81e-5}},
    {"double torus", {2.25e-3, 9.60e-4, 3.76e-4, 1.53e-4}},
    {"triple torus", {4.55e-3, 1.89e-3, 6.55e-4, 2.46e-4}},
    {"cup (U shape)", {9.60e-4, 4.44e-3, 2.46e-3, 1.29e-3}},
    {"two spheres", {1.58e-3, 5.43e-4, 1.99e-4, 8.02e-5}},
    // The plate (0.04 thick) is the one shape whose control mesh moves with
    // any small change of its points: level 0 measured 1.11e-4 first,
    // 1.79e-4 by 51be302, 2.5e-4 once the off-plane outlier test took 6 of
    // its 20,000 points (1.82e-4 with none taken).  Its own figure here is
    // 1.79e-4, so the bound is twice the middle of that range.
    {"thin plate", {1.79e-4, 2.84e-3, 3.65e-3, 3.15e-3}},
};
constexpr double kMargin = 2.0;

}  // namespace

TEST_CASE("closed loop: the decoder reproduces the encoder's levels bit for bit, and each level is closer to the points") {
  for (int shape : {1, 2}) {  // torus, double torus
    const test::Shape s = test::genus_shapes()[shape];
    INFO(s.name);
    const PointCloud pc = test::sample_sdf(s.sdf, s.lo, s.hi, 30000);
    auto stages = build_control_mesh(pc);
    REQUIRE(stages.ok());
    auto draco = encode_control_mesh(stages.value().control, {});
    REQUIRE(draco.ok());
    auto control = decode_control_mesh(draco.value(), 1 << 20, 1 << 20);
    REQUIRE(control.ok());
    const PointIndex index(pc);
    const double diagonal = std::sqrt(3.0) * (s.hi - s.lo);
    LevelEncodeOptions o;
    o.levels = 3;
    o.step = quantization_step(1e-4, diagonal);
    auto enc = encode_levels(control.value(), index, o);
    REQUIRE(enc.ok());

    format::FileContents c;
    auto topo = build_topology(static_cast<uint32_t>(control.value().vertex_count()), control.value().triangles);
    REQUIRE(topo.ok());
    c.header.level_count = 3;
    c.header.control_vertex_count = static_cast<uint32_t>(control.value().vertex_count());
    c.header.control_edge_count = topo.value().edge_count();
    c.header.control_triangle_count = static_cast<uint32_t>(control.value().triangle_count());
    c.header.bbox_min = {float(s.lo), float(s.lo), float(s.lo)};
    c.header.bbox_max = {float(s.hi), float(s.hi), float(s.hi)};
    c.control_mesh = draco.value();
    c.levels = enc.value().levels;
    c.header.version_minor = format::minimum_version_minor(c);  // 2 when a level chose the context coder
    auto file = format::serialize(c);
    REQUIRE(file.ok());
    // The bytes choose_coding kept make the same file as compressing each
    // level again, and the writer's table of contents is the one a reader
    // finds in it.
    c.level_data = enc.value().chunks;
    auto reused = format::serialize_with_toc(c);
    REQUIRE(reused.ok());
    CHECK(reused.value().bytes == file.value());
    CHECK(reused.value().toc == format::read_all(file.value()).toc());
    std::swap(c.level_data[0], c.level_data[1]);  // another level's data is refused
    CHECK(format::serialize(c).status().code() == ErrorCode::invalid_argument);

    ProgressiveDecoder d;
    REQUIRE(d.feed(file.value()).ok());
    double previous = 1e30;
    for (uint32_t l = 0; l <= 3; ++l) {
      auto mesh = d.decode(l);
      REQUIRE(mesh.ok());
      const auto& want = enc.value().positions[l];
      REQUIRE(mesh.value().positions.size() == want.size());
      CHECK(std::equal(want.begin(), want.end(), mesh.value().positions.begin()));
      CHECK(std::equal(enc.value().triangles[l].begin(), enc.value().triangles[l].end(), mesh.value().triangles.begin()));
      // The points' distance to the level's surface shrinks level by level.
      const double dist = points_to_mesh(pc.xyz, {want, enc.value().triangles[l]}).mean;
      INFO("level " << l << ": mean point-to-surface distance " << dist / diagonal << " of the diagonal");
      if (l >= 1) {
        const LevelStats& st = enc.value().stats[l - 1];
        CHECK(st.clamped * 100 < st.odd);  // under 1% clamped
        CHECK(dist < previous);
      }
      previous = dist;
      // Vertices stay on the true surface.
      double off = 0;
      for (size_t v = 0; v < want.size() / 3; ++v) off += std::abs(s.sdf(want[3 * v], want[3 * v + 1], want[3 * v + 2]));
      off /= static_cast<double>(want.size() / 3);
      INFO("vertex offset " << off / diagonal << " of the diagonal");
      CHECK(off < kMargin * measured(kVertexOffset, std::size(kVertexOffset), s.name, l) * diagonal);
    }
    INFO("level 3: points to surface " << previous / diagonal << " of the diagonal");
    CHECK(previous < kMargin * measured(kClosedLoopLevel3, std::size(kClosedLoopLevel3), s.name, 3) * diagonal);
  }
}

TEST_CASE("error bounds on every test shape: smooth shapes get closer level by level") {
  // Points -> surface mean distance relative to the diagonal, exact.  The
  // smooth shapes (spheres, tori) approach the points at every level; the
  // cup and the thin plate have sharp creases where the butterfly
  // overshoots and the clamped displacements cannot pull it back (the
  // paper's own caveat for CAD-like shapes), so they only stay bounded.
  for (const test::Shape& s : test::genus_shapes()) {
    INFO(s.name);
    const PointCloud pc = test::sample_sdf(s.sdf, s.lo, s.hi, 20000);
    EncodeOptions o;
    o.levels = 3;
    // The bounds below are per level index, recorded over the default face
    // count; a quarter of the faces (choose_control) puts level l at a
    // quarter of the vertices.  With it the creased cup kept the quarter and
    // came 2.5-8% over its level 2-3 bounds (issue 15, h4-rd): the choice's
    // own guard is level_error_test.cpp.
    o.choose_control = false;
    auto e = encode_points(pc, o);
    REQUIRE(e.ok());
    // The table of contents the writer reported is the file's, and every
    // level used the one step encode_points resolved.
    CHECK(e.value().toc == format::read_all(e.value().bytes).toc());
    for (const format::Level& level : e.value().levels.levels) CHECK(level.step == e.value().step);
    const PointIndex index(pc);
    const bool creased = std::string(s.name) == "cup (U shape)" || std::string(s.name) == "thin plate";
    double prev = 1;
    for (uint32_t l = 0; l <= 3; ++l) {
      INFO("level " << l);
      const TwoSidedDistance d = two_sided_distance(index, {e.value().levels.positions[l], e.value().levels.triangles[l]});
      const double rel = d.points_to_mesh_mean / e.value().diagonal;
      INFO("points to surface " << rel << " of the diagonal");
      CHECK(rel < kMargin * measured(kPointsToSurface, std::size(kPointsToSurface), s.name, l));
      if (creased) continue;
      if (l > 0) CHECK(rel < 0.7 * prev);  // measured: at most 0.46
      prev = rel;
      if (l > 0) CHECK(e.value().levels.stats[l - 1].clamped * 50 < e.value().levels.stats[l - 1].odd);
    }
  }
}

TEST_CASE("control mesh bits follow level 0's distance to the points, never finer than the step's") {
  TriangleMesh cube;  // only the extent matters: 2 along x
  cube.positions = {-1, 0, 0, 1, 0.5f, 0, 0, 1, 0.25f};
  cube.triangles = {0, 1, 2};
  CHECK(control_bits_for_step(cube, 2.0f / 1000) == 10);   // 2^10 = 1024 >= 1000 steps
  CHECK(control_bits_for_step(cube, 2.0f / 1025) == 11);
  CHECK(control_bits_for_step(cube, 1.0f) == 8);            // never under 8
  CHECK(control_bits_for_step(cube, 1e-9f) == 16);          // never over the old fixed 16
  // The point path: a grid of kControlGridPerError times level 0's distance.
  const double d = 2.0 / 1000 / kControlGridPerError;         // a grid of 2/1000: 10 bits
  CHECK(control_bits_for_error(cube, d, 2.0f / 5000) == 10);
  CHECK(control_bits_for_error(cube, 2.0 / 1023 / kControlGridPerError, 2.0f / 5000) == 10);
  CHECK(control_bits_for_error(cube, 2.0 / 1025 / kControlGridPerError, 2.0f / 5000) == 11);
  CHECK(control_bits_for_error(cube, d, 2.0f / 300) == 9);    // never finer than the step's
  CHECK(control_bits_for_error(cube, 0.0, 2.0f / 5000) == 13);  // no distance: the step's
  CHECK(control_bits_for_error(cube, NAN, 2.0f / 5000) == 13);
  CHECK(control_bits_for_error(cube, 10.0, 2.0f / 5000) == 8);  // never under 8

  const test::Shape s = test::genus_shapes()[1];
  const PointCloud pc = test::sample_sdf(s.sdf, s.lo, s.hi, 20000);
  EncodeOptions o;
  o.levels = 1;
  // The level-0 rule alone: with the control choice on, a clean cloud's
  // bits may then go under it (choose_control_bits, control_choice_test).
  o.choose_control = false;
  auto e = encode_points(pc, o);
  REQUIRE(e.ok());
  const Encoding& enc = e.value();
  // Level 0's distance to the points, as the encoder measures it: the mean
  // of the points' distance to the control mesh and its vertices' to their
  // 8 nearest points' plane.
  const PointIndex index(pc);
  const TriangleTree tree(enc.stages.control);
  double to_mesh = 0;
  for (size_t i = 0; i < pc.size(); ++i) {
    const double p[3] = {pc.xyz[3 * i], pc.xyz[3 * i + 1], pc.xyz[3 * i + 2]};
    to_mesh += tree.distance(p);
  }
  const double level0 = 0.5 * (to_mesh / static_cast<double>(pc.size()) +
                               vertices_to_points_surface(enc.stages.control.positions, index).mean);
  INFO("level 0 " << level0 << ", step " << enc.step << ", bits " << enc.control_bits);
  CHECK(enc.control_bits == control_bits_for_error(enc.stages.control, level0, enc.step));
  CHECK(enc.control_bits < control_bits_for_step(enc.stages.control, enc.step));  // level 0 is far coarser than the step here
  CHECK(format::read_all(enc.bytes).header().control_position_bits == enc.control_bits);
  // Every decoded control vertex lies within a grid spacing and a half of
  // sliding along the surface plus half a spacing off it (per coordinate,
  // plus binary32 rounding) of a vertex the encoder built, and within half
  // a spacing when Draco rounds it to the nearest grid point; the spacing is
  // at most kControlGridPerError times level 0's distance.
  const auto worst_rounding = [&](const Encoding& x) {
    const std::vector<float>& before = x.stages.control.positions;
    double worst = 0;
    for (size_t v = 0; v < x.control.vertex_count(); ++v) {
      double best = 1e30;
      for (size_t w = 0; w < before.size() / 3; ++w) {
        double d = 0;
        for (int a = 0; a < 3; ++a) d = std::max(d, std::abs(double{x.control.positions[3 * v + a]} - before[3 * w + a]));
        best = std::min(best, d);
      }
      worst = std::max(worst, best);
    }
    return worst;
  };
  const double grid = kControlGridPerError * level0 * 1.01;
  INFO("worst control vertex rounding " << worst_rounding(enc) << ", grid at most " << grid);
  CHECK(worst_rounding(enc) <= (kRoundingSlide + 0.5) * grid);
  // Along the normal the chosen grid points are far nearer the surface than
  // the nearest ones.
  INFO("mean offset along the normal " << enc.rounding.chosen_normal << ", plain rounding " << enc.rounding.nearest_normal);
  CHECK(enc.rounding.vertices == enc.control.vertex_count());
  CHECK(enc.rounding.chosen_normal < 0.5 * enc.rounding.nearest_normal);
  o.round_along_surface = false;
  auto plain = encode_points(pc, o);
  REQUIRE(plain.ok());
  CHECK(plain.value().control_bits == enc.control_bits);
  CHECK(worst_rounding(plain.value()) <= 0.5 * grid);
  o.round_along_surface = true;

  // Given bits are kept.
  o.control_bits = 16;
  auto f = encode_points(pc, o);
  REQUIRE(f.ok());
  CHECK(f.value().control_bits == 16);
}

TEST_CASE("auto levels: up to the first level with more vertices than points, 1..8") {
  const format::MeshCounts control{100, 300, 200};  // closed: V - E + F = 0
  // Level 1: 400 vertices, level 2: 1600, level 3: 6400.
  CHECK(auto_levels(control, 50) == 1);
  CHECK(auto_levels(control, 400) == 2);  // level 1 has exactly as many: not more
  CHECK(auto_levels(control, 1000) == 2);
  CHECK(auto_levels(control, 1600) == 3);
  CHECK(auto_levels(control, size_t{1} << 40) == format::kMaxLevelsInPractice);
}
