// Crease tags (format 1.1, spec/decoding.md section 5.4): flat faces between
// creases stay flat, creases follow their polyline, corners stay put, every
// decoding path gives the same bits, and files without tags are unchanged.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "../crease_shapes.h"
#include "../shapes.h"
#include "butterfly.h"
#include "dbss/decoder/level_refiner.h"
#include "dbss/decoder/progressive.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/control_mesh_codec.h"
#include "dbss/decoder/control_mesh.h"
#include "dbss/format/reader.h"
#include "dbss/format/writer.h"
#include "file_builder.h"
#include "kernel_choice.h"
#include "reference.h"

using namespace dbss;

namespace {

// Plain subdivision (every q = 0) through the decoder's own refinement.
std::vector<std::vector<float>> plain_levels(const TriangleMesh& m, const format::Creases& c, int levels,
                                             unsigned threads = 1, Kernels k = Kernels::best) {
  auto r = LevelRefiner::create(m, c, {k});
  REQUIRE(r.ok());
  std::vector<std::vector<float>> out{m.positions};
  std::vector<int32_t> q;
  const OddChooser zero = [](uint32_t, const double*, const double*, const float*, const float*) { return 0; };
  for (int l = 0; l < levels; ++l) {
    r.value().refine(zero, 1e-3f, q, threads);
    out.emplace_back(r.value().positions().begin(), r.value().positions().end());
  }
  return out;
}

// Largest distance of a point of [-1,1]^3 to the cube's surface, over points.
double off_cube(const std::vector<float>& p) {
  double worst = 0;
  for (size_t i = 0; i < p.size(); i += 3) {
    const double m = std::max({std::abs(p[i]), std::abs(p[i + 1]), std::abs(p[i + 2])});
    worst = std::max(worst, std::abs(m - 1.0));
  }
  return worst;
}

format::Creases cube_creases() { return test::creases_from_dihedral(test::cube(), 30); }

}  // namespace

TEST_CASE("creases from dihedral angles: the cube's 12 edges and 8 corners, none on a torus") {
  const format::Creases c = cube_creases();
  CHECK(std::count(c.edge.begin(), c.edge.end(), 1) == 12);
  CHECK(std::count(c.corner.begin(), c.corner.end(), 1) == 8);
  const format::Creases t = test::creases_from_dihedral(test::torus(32, 24), 30);
  CHECK(std::count(t.edge.begin(), t.edge.end(), 1) == 0);
}

TEST_CASE("a tagged cube stays a cube at every level, an untagged one rounds off") {
  const auto tagged = plain_levels(test::cube(), cube_creases(), 4);
  for (size_t l = 0; l < tagged.size(); ++l) {
    INFO("level " << l);
    CHECK(off_cube(tagged[l]) < 1e-6);
  }
  // The control vertices (corners) never move.
  for (size_t i = 0; i < 24; ++i) CHECK(tagged.back()[i] == test::cube().positions[i]);
  const auto smooth = plain_levels(test::cube(), {}, 3);
  CHECK(off_cube(smooth.back()) > 0.05);  // the test can fail: without tags the cube is not kept
}

TEST_CASE("crease flags are inherited: halves of creases are creases, inner edges never") {
  auto t = build_topology(8, test::cube().triangles).value();
  const format::Creases c = cube_creases();
  REQUIRE(set_creases(t, c.edge, c.corner).ok());
  for (int l = 1; l <= 3; ++l) {
    t = refine_topology(t);
    const auto creases = std::count(t.edge_crease.begin(), t.edge_crease.end(), 1);
    CHECK(creases == 12 << l);
    size_t sharp = 0, ends = 0;
    for (uint8_t k : t.vertex_boundary) sharp += (k & kVertexSharp) != 0, ends += (k & kVertexCreaseEnd) != 0;
    CHECK(sharp == size_t(8 + 12 * ((1 << l) - 1)));
    CHECK(ends == 8);
    // Every crease edge joins two sharp vertices.
    for (uint32_t e = 0; e < t.edge_count(); ++e)
      if (t.edge_crease[e]) {
        const uint32_t h = t.edge_half[e];
        CHECK((t.vertex_boundary[t.triangles[h]] & kVertexSharp));
        CHECK((t.vertex_boundary[t.triangles[next_half(h)]] & kVertexSharp));
      }
  }
}

TEST_CASE("a capped cylinder keeps flat caps, and its rims follow the circle") {
  const TriangleMesh m = test::capped_cylinder(24, 3);
  const format::Creases c = test::creases_from_dihedral(m, 30);
  CHECK(std::count(c.edge.begin(), c.edge.end(), 1) == 48);  // the two rims
  CHECK(std::count(c.corner.begin(), c.corner.end(), 1) == 0);
  const auto levels = plain_levels(m, c, 3);
  const auto untagged = plain_levels(m, {}, 3);
  // Vertices at the caps' height or beyond: with tags exactly the flat caps.
  const auto cap_error = [](const std::vector<float>& p) {
    double worst = 0;
    for (size_t i = 0; i < p.size(); i += 3) worst = std::max(worst, std::abs(p[i + 2]) - 1.0);
    return worst;
  };
  CHECK(cap_error(levels.back()) <= 0);
  CHECK(cap_error(untagged.back()) > 0.01);
  // Rim vertices (the sharp ones) are much closer to the unit circle than
  // the control polygon's chord midpoints (at cos(7.5 deg) = 0.9914).
  auto t = build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles).value();
  REQUIRE(set_creases(t, c.edge, c.corner).ok());
  for (int l = 0; l < 3; ++l) t = refine_topology(t);
  double rim = 0;
  size_t on_rim = 0;
  const auto& p = levels.back();
  for (uint32_t v = 0; v < t.vertex_count; ++v)
    if (t.vertex_boundary[v] & kVertexSharp) {
      CHECK(std::abs(p[3 * v + 2]) == 1.0f);
      rim = std::max(rim, std::abs(std::hypot(p[3 * v], p[3 * v + 1]) - 1.0)), ++on_rim;
    }
  CHECK(on_rim == 2 * 24 * 8);
  CHECK(rim < 0.1 * (1 - std::cos(3.14159265358979323846 / 24)));
}

TEST_CASE("crease stencils: every row sums to 1, the fast path and the generic one agree bit for bit") {
  struct Case {
    TriangleMesh m;
    format::Creases c;
  };
  std::vector<Case> cases{{test::cube(), cube_creases()},
                          {test::capped_cylinder(10, 4), test::creases_from_dihedral(test::capped_cylinder(10, 4), 30)},
                          {test::roof_block(4), test::creases_from_dihedral(test::roof_block(4), 30)}};
  // A dart: one crease edge ending inside a smooth torus, and a corner tag alone.
  {
    TriangleMesh t = test::torus(8, 6);
    auto topo = build_topology(static_cast<uint32_t>(t.vertex_count()), t.triangles).value();
    format::Creases c{std::vector<uint8_t>(topo.edge_count(), 0), std::vector<uint8_t>(topo.vertex_count, 0)};
    c.edge[0] = c.edge[5] = 1;
    c.corner[7] = 1;
    cases.push_back({t, c});
  }
  for (const Case& k : cases) {
    auto t = build_topology(static_cast<uint32_t>(k.m.vertex_count()), k.m.triangles).value();
    REQUIRE(set_creases(t, k.c.edge, k.c.corner).ok());
    std::vector<float> p = k.m.positions;
    for (int l = 0; l < 3; ++l) {
      const Stencils fast = build_stencils(t), generic = build_stencils(t, true);
      std::vector<uint32_t> idx;
      std::vector<double> w;
      for (uint32_t e = 0; e < generic.size(); ++e) {
        stencil_terms(generic, e, idx, w);
        double sum = 0;
        for (double x : w) sum += x;
        CHECK(std::abs(sum - 1) < 1e-12);
      }
      std::vector<float> a(3 * size_t{t.edge_count()}), b(a.size());
      apply_stencils(fast, p.data(), 0, uint32_t(fast.regular_odd.size()), 0, uint32_t(fast.other_odd.size()), a.data());
      apply_stencils(generic, p.data(), 0, 0, 0, uint32_t(generic.other_odd.size()), b.data());
      CHECK(a == b);
      // ... and equal to the refiner's (the progressive decoder's kernels).
      p.insert(p.end(), a.begin(), a.end());
      t = refine_topology(t);
    }
    for (unsigned threads : {1u, 3u})
      for (Kernels kern : {Kernels::best, Kernels::baseline}) CHECK(plain_levels(k.m, k.c, 3, threads, kern)[3] == p);
  }
}

TEST_CASE("a crease on a boundary edge is bad_mesh") {
  const TriangleMesh g = test::planar_grid(3, 3);
  auto t = build_topology(static_cast<uint32_t>(g.vertex_count()), g.triangles).value();
  std::vector<uint8_t> edge(t.edge_count(), 0), corner(t.vertex_count, 0);
  uint32_t e = 0;
  while (t.twin[t.edge_half[e]] != kNoHalfEdge) ++e;
  edge[e] = 1;
  CHECK(set_creases(t, edge, corner).code() == ErrorCode::bad_mesh);
  std::vector<uint8_t> short_edge(3, 0);
  CHECK(set_creases(t, short_edge, corner).code() == ErrorCode::bad_mesh);
}

namespace {

// A 1.1 file with creases and random displacements, built as the encoder
// builds one: from the Draco-decoded control mesh.
struct CreaseFile {
  std::vector<uint8_t> bytes;
  TriangleMesh control;
  format::Creases creases;
  std::vector<format::Level> levels;
};

CreaseFile crease_file(const TriangleMesh& shape, uint8_t level_count) {
  CreaseFile f;
  auto draco = encode_control_mesh(shape, {});
  f.control = decode_control_mesh(draco.value(), 1 << 24, 1 << 24).value();
  f.creases = test::creases_from_dihedral(f.control, 30);
  auto topo = build_topology(static_cast<uint32_t>(f.control.vertex_count()), f.control.triangles).value();
  format::FileContents c;
  c.header.version_minor = format::kCreaseVersionMinor;
  c.header.level_count = level_count;
  c.header.control_vertex_count = static_cast<uint32_t>(f.control.vertex_count());
  c.header.control_edge_count = topo.edge_count();
  c.header.control_triangle_count = static_cast<uint32_t>(f.control.triangle_count());
  c.header.bbox_min = {-2, -2, -2};
  c.header.bbox_max = {2, 2, 2};
  c.control_mesh = std::move(draco).value();
  c.creases = f.creases;
  const format::MeshCounts control{c.header.control_vertex_count, c.header.control_edge_count,
                                   c.header.control_triangle_count};
  uint32_t s = 99;
  for (uint8_t l = 1; l <= level_count; ++l) {
    format::Level level;
    level.index = l;
    level.step = 1e-3f;
    level.q.resize(*format::odd_vertex_count(control, l));
    for (auto& q : level.q) {
      s = s * 1664525u + 1013904223u;
      q = static_cast<int32_t>((s >> 8) % 41) - 20;
    }
    c.levels.push_back(level);
  }
  f.levels = c.levels;
  f.bytes = format::serialize(c).value();
  return f;
}

}  // namespace

TEST_CASE("a 1.1 file with creases decodes as the refiner with its tags places it, on any prefix") {
  const CreaseFile f = crease_file(test::roof_block(4), 3);
  auto r = format::read_all(f.bytes);
  REQUIRE(r.status().ok());
  CHECK(r.header().version_minor == 1);
  REQUIRE(r.has_creases());
  CHECK(r.creases() == f.creases);
  // The encoder's view: the refiner with the tags and the file's q.
  auto refiner = LevelRefiner::create(f.control, f.creases).value();
  std::vector<std::vector<float>> expect{f.control.positions};
  for (const format::Level& level : f.levels) {
    std::vector<int32_t> q;
    size_t i = 0;
    const OddChooser from_file = [&](uint32_t e, const double*, const double*, const float*, const float*) {
      (void)i;
      return level.q[e];
    };
    refiner.refine(from_file, level.step, q);
    expect.emplace_back(refiner.positions().begin(), refiner.positions().end());
  }
  for (unsigned threads : {1u, 2u}) {
    DecoderOptions o;
    o.threads = threads;
    o.kernels = test::kernels_under_test();
    ProgressiveDecoder d(o);
    // Byte by byte up to the end of CTRL: level 0 before the tags arrive.
    size_t at = 0;
    while (d.ready_level() < 0) REQUIRE(d.feed(std::span<const uint8_t>(&f.bytes[at++], 1)).ok());
    auto l0 = d.decode(0);
    REQUIRE(l0.ok());
    CHECK(std::equal(expect[0].begin(), expect[0].end(), l0.value().positions.begin()));
    REQUIRE(d.feed(std::span<const uint8_t>(f.bytes).subspan(at)).ok());
    for (uint32_t l = 1; l <= 3; ++l) {
      auto v = d.decode(l);
      REQUIRE(v.ok());
      CHECK(std::equal(expect[l].begin(), expect[l].end(), v.value().positions.begin(), v.value().positions.end()));
    }
  }
  // Without the tags the same q give other meshes: the tags are used.
  auto plain = LevelRefiner::create(f.control).value();
  std::vector<int32_t> q;
  const OddChooser first = [&](uint32_t e, const double*, const double*, const float*, const float*) {
    return f.levels[0].q[e];
  };
  plain.refine(first, f.levels[0].step, q);
  CHECK(!std::equal(expect[1].begin(), expect[1].end(), plain.positions().begin()));
}

TEST_CASE("CREA: a 1.0 file may not have it, and its placement and fields are checked in the spec's order") {
  const CreaseFile f = crease_file(test::cube(), 1);
  auto r = format::read_all(f.bytes);
  REQUIRE(r.status().ok());
  // Rebuild the body with changes (assemble recomputes the CRCs).
  std::vector<format::RawChunk> body;
  for (const format::TocEntry& e : r.toc())
    body.push_back({e.type, std::vector<uint8_t>(f.bytes.begin() + e.offset + 8, f.bytes.begin() + e.offset + 8 + e.length)});
  REQUIRE(body[1].type == format::kCrea);
  const std::vector<uint8_t> head(f.bytes.begin() + 16, f.bytes.begin() + 16 + 56);
  const auto code = [&](std::vector<uint8_t> h, std::vector<format::RawChunk> b) {
    return format::read_all(format::assemble(h, b)).status().code();
  };
  CHECK(code(head, body) == ErrorCode::ok);
  std::vector<uint8_t> v10 = head;
  v10[2] = 0;  // version_minor 0: CREA is unknown there, as to a 1.0 reader
  CHECK(code(v10, body) == ErrorCode::unknown_critical_chunk);
  auto swapped = body;
  std::swap(swapped[1], swapped[2]);  // CREA after LEVL
  CHECK(code(head, swapped) == ErrorCode::bad_structure);
  auto twice = body;
  twice.insert(twice.begin() + 1, body[1]);
  CHECK(code(head, twice) == ErrorCode::bad_structure);
  auto first = body;
  std::swap(first[0], first[1]);  // CREA before CTRL
  CHECK(code(head, first) == ErrorCode::bad_structure);
  const auto with_data = [&](auto change) {
    auto b = body;
    change(b[1].data);
    return code(head, b);
  };
  CHECK(with_data([](std::vector<uint8_t>& d) { d.push_back(0); }) == ErrorCode::bad_field);  // length
  CHECK(with_data([](std::vector<uint8_t>& d) { d[0] = 1; }) == ErrorCode::bad_field);        // coding
  CHECK(with_data([](std::vector<uint8_t>& d) { d[2] = 1; }) == ErrorCode::bad_field);        // reserved
  CHECK(with_data([](std::vector<uint8_t>& d) { d[4] ^= 1; }) == ErrorCode::bad_field);       // crease_count
  // 18 edges: bits 2..7 of the edge map's third byte are padding.
  CHECK(with_data([](std::vector<uint8_t>& d) { d[12 + 2] |= 0x80; }) == ErrorCode::bad_field);
  CHECK(with_data([](std::vector<uint8_t>& d) { std::fill(d.begin() + 4, d.end(), 0); }) == ErrorCode::bad_field);
  // A crease on ... the cube has no boundary; a tag list for the wrong mesh
  // cannot pass the length check, so a well-formed CREA always fits its mesh
  // in size; the boundary rule is tested with set_creases above.
}

TEST_CASE("files without creases are written as 1.0, byte for byte as before") {
  const std::vector<uint8_t> bytes = test::build_file(test::icosahedron(), 2, 5, 1e-2f);
  auto r = format::read_all(bytes);
  REQUIRE(r.status().ok());
  CHECK(r.header().version_minor == 0);
  CHECK(!r.has_creases());
  for (const format::TocEntry& e : r.toc()) CHECK(!(e.type == format::kCrea));
}

TEST_CASE("the spec's reference decoder (spec/reference) gives the refiner's bits with creases, displaced or not") {
  std::vector<std::pair<TriangleMesh, format::Creases>> cases{
      {test::cube(), cube_creases()},
      {test::roof_block(4), test::creases_from_dihedral(test::roof_block(4), 30)},
      {test::capped_cylinder(10, 4), test::creases_from_dihedral(test::capped_cylinder(10, 4), 30)}};
  {
    TriangleMesh t = test::torus(8, 6);  // a dart (one crease edge ending) and a lone corner tag
    auto topo = build_topology(static_cast<uint32_t>(t.vertex_count()), t.triangles).value();
    format::Creases c{std::vector<uint8_t>(topo.edge_count(), 0), std::vector<uint8_t>(topo.vertex_count, 0)};
    c.edge[0] = c.edge[5] = c.edge[9] = 1;
    c.corner[7] = 1;
    cases.push_back({t, c});
  }
  for (const auto& [m, c] : cases) {
    for (int32_t amplitude : {0, 30}) {
      auto r = LevelRefiner::create(m, c).value();
      dbss_ref::Mesh ref{m.positions, m.triangles, c.edge, c.corner};
      uint32_t s = 7;
      for (int l = 0; l < 3; ++l) {
        std::vector<int32_t> q;
        if (amplitude) {
          q.resize(r.next_odd_count());
          for (auto& v : q) s = s * 1664525u + 1013904223u, v = static_cast<int32_t>((s >> 8) % 61) - 30;
        }
        const OddChooser from_q = [&](uint32_t e, const double*, const double*, const float*, const float*) {
          return q.empty() ? 0 : q[e];
        };
        std::vector<int32_t> used;
        r.refine(from_q, 1e-3f, used);
        ref = dbss_ref::subdivide(ref, q, 1e-3f);
        INFO("level " << l + 1 << " amplitude " << amplitude);
        REQUIRE(ref.triangles.size() == r.triangles().size());
        CHECK(std::equal(ref.positions.begin(), ref.positions.end(), r.positions().begin(), r.positions().end()));
      }
    }
  }
}
