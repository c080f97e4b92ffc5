// Format 1.3: BDRY chunks (spec/dbss-format.md section 9c) and the move
// across the boundary (spec/decoding.md section 7a), in the project's
// decoder and the reference decoder: where the vertices go, the version
// rule, and the error code and offset of hostile BDRY bytes.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "../reference/project_decode.h"
#include "../shapes.h"
#include "dbss/decoder/progressive.h"
#include "dbss/decoder/topology.h"
#include "dbss/format/crc32c.h"
#include "dbss/format/reader.h"
#include "dbss/format/writer.h"
#include "file_builder.h"
#include "reference.h"

using namespace dbss;

namespace {

// A 1.0/1.2 file of an open grid (boundary on all four sides), 2 levels.
format::FileContents grid_contents() {
  const auto bytes = test::build_file(test::jitter(test::planar_grid(5, 4), 0.2f), 2, 30, 0.05f);
  format::Reader r = format::read_all(bytes);
  REQUIRE(r.complete());
  format::FileContents c;
  c.header = r.header();
  c.control_mesh.assign(r.control_payload().begin(), r.control_payload().end());
  for (uint32_t l = 1; l <= r.levels_ready(); ++l) c.levels.push_back(r.level(l));
  return c;
}

std::vector<uint8_t> to_bytes(format::FileContents c) {
  c.header.version_minor = format::minimum_version_minor(c);
  auto bytes = format::serialize(c);
  REQUIRE(bytes.ok());
  return bytes.value();
}

std::vector<float> decode_level(const std::vector<uint8_t>& bytes, uint32_t level) {
  const test::ProjectDecode d = test::project_decode(bytes);
  REQUIRE(d.error.empty());
  REQUIRE(d.levels.size() > level);
  return d.levels[level].positions;
}

uint64_t boundary_edges_of_level(const format::Header& h, uint32_t level) {
  return *format::boundary_edge_count({h.control_vertex_count, h.control_edge_count, h.control_triangle_count}, level);
}

// The file's chunk `type` (the first one): its file offset.
uint64_t chunk_offset(const std::vector<uint8_t>& bytes, format::ChunkType type) {
  format::Reader r = format::read_all(bytes);
  for (const format::TocEntry& e : r.toc())
    if (e.type == type) return e.offset;
  FAIL("no such chunk");
  return 0;
}

// Rewrites a chunk's CRC after a test changed its data.
void fix_crc(std::vector<uint8_t>& bytes, uint64_t at) {
  uint32_t length;
  std::memcpy(&length, &bytes[at], 4);
  const uint32_t crc = format::crc32c(std::span<const uint8_t>(&bytes[at], 8 + size_t{length}));
  std::memcpy(&bytes[at + 8 + length], &crc, 4);
}

struct Outcome {
  std::string code;
  uint64_t offset = 0;
};

Outcome read_outcome(const std::vector<uint8_t>& bytes) {
  format::Reader r = format::read_all(bytes);
  if (r.complete()) return {};
  return {error_code_name(r.status().code()), r.status().offset()};
}

}  // namespace

TEST_CASE("BDRY: boundary odd vertices move across the boundary within the surface, nothing else moves",
          "[boundary_values]") {
  format::FileContents plain = grid_contents();
  const format::Header h = plain.header;
  format::FileContents moved = plain;
  format::Level& l1 = moved.levels[0];
  l1.boundary.step = 0.01f;
  l1.boundary.coding = format::DisplacementCoding::context;
  l1.boundary.q.resize(boundary_edges_of_level(h, 0));
  for (size_t k = 0; k < l1.boundary.q.size(); ++k) l1.boundary.q[k] = static_cast<int32_t>(k % 7) - 3;
  const auto a = to_bytes(plain), b = to_bytes(moved);
  CHECK(format::read_all(a).header().version_minor < format::kBoundaryVersionMinor);
  CHECK(format::read_all(b).header().version_minor == format::kBoundaryVersionMinor);

  // Level 0 is the same; at level 1 only the boundary odd vertices moved,
  // each by |p| * step, perpendicular to its edge.
  CHECK(decode_level(a, 0) == decode_level(b, 0));
  const std::vector<float> pa = decode_level(a, 1), pb = decode_level(b, 1);
  const std::vector<float> p0 = decode_level(a, 0);
  REQUIRE(pa.size() == pb.size());
  const TriangleMesh control = test::project_decode(a).levels[0];
  auto topo = build_topology(static_cast<uint32_t>(control.vertex_count()), control.triangles);
  REQUIRE(topo.ok());
  const LevelTopology& t = topo.value();
  const uint32_t V = t.vertex_count;
  size_t k = 0, moved_count = 0;
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    const uint32_t hh = t.edge_half[e];
    const float* ma = &pa[3 * (size_t{V} + e)];
    const float* mb = &pb[3 * (size_t{V} + e)];
    if (t.twin[hh] != kNoHalfEdge) {
      CHECK(std::memcmp(ma, mb, 12) == 0);
      continue;
    }
    const int32_t p = l1.boundary.q[k++];
    const float* u = &p0[3 * size_t{t.triangles[hh]}];
    const float* w = &p0[3 * size_t{t.triangles[next_half(hh)]}];
    double d[3], tv[3], len = 0, dot = 0, tl = 0;
    for (int i = 0; i < 3; ++i) {
      d[i] = double{mb[i]} - ma[i], tv[i] = double{w[i]} - u[i];
      len += d[i] * d[i], dot += d[i] * tv[i], tl += tv[i] * tv[i];
    }
    len = std::sqrt(len), tl = std::sqrt(tl);
    CHECK(len == Approx(std::abs(p) * 0.01).margin(1e-6));
    CHECK(std::abs(dot) <= 1e-5 * tl);
    if (p == 0) CHECK(std::memcmp(ma, mb, 12) == 0);  // a zero leaves the vertex's bits as they were
    moved_count += p != 0;
  }
  CHECK(k == l1.boundary.q.size());
  CHECK(moved_count > 10);

  // The reference decoder, written from the spec alone, computes the same bits.
  const dbss_ref::Decoded ref = dbss_ref::decode(b);
  REQUIRE(ref.error.empty());
  const test::ProjectDecode mine = test::project_decode(b);
  REQUIRE(mine.error.empty());
  REQUIRE(ref.levels.size() == mine.levels.size());
  for (size_t l = 0; l < ref.levels.size(); ++l) CHECK(ref.levels[l].positions == mine.levels[l].positions);
}

TEST_CASE("BDRY: all zeros decode as no chunk", "[boundary_values]") {
  format::FileContents plain = grid_contents();
  format::FileContents zeros = plain;
  zeros.levels[1].boundary.step = 0.01f;
  zeros.levels[1].boundary.q.assign(boundary_edges_of_level(plain.header, 1), 0);
  const auto a = to_bytes(plain), b = to_bytes(zeros);
  CHECK(a != b);
  for (uint32_t l = 0; l <= 2; ++l) CHECK(decode_level(a, l) == decode_level(b, l));
}

TEST_CASE("BDRY: a file that says 1.2 has an unknown critical chunk, as a 1.2 reader finds", "[boundary_values]") {
  const auto bytes = test::build_file(test::jitter(test::planar_grid(5, 4), 0.2f), 2, 30, 0.05f, 1, 0, false, 5);
  REQUIRE(read_outcome(bytes).code.empty());
  std::vector<uint8_t> old = bytes;
  old[8 + 8 + 2] = 2;  // HEAD's version_minor
  fix_crc(old, 8);
  const Outcome o = read_outcome(old);
  CHECK(o.code == "unknown_critical_chunk");
  // Reported at the table of contents' first BDRY entry (the first body
  // entry after CTRL): INDX data starts at 8 + 12 + 56 + 8.
  CHECK(o.offset == 8 + 12 + 56 + 8 + 16 + 16);
  CHECK(dbss_ref::decode(old).error == "unknown_critical_chunk");
}

TEST_CASE("BDRY: hostile fields give the spec's code and offset, in both decoders", "[boundary_values]") {
  const auto good = test::build_file(test::jitter(test::planar_grid(5, 4), 0.2f), 2, 30, 0.05f, 1, 0, false, 5);
  const uint64_t at = chunk_offset(good, format::kBdry);  // level 1's BDRY
  const uint64_t data = at + 8;
  struct Case {
    const char* what;
    size_t byte;
    uint8_t value;
    const char* code;
    uint64_t offset;
  };
  const Case cases[] = {
      {"level index", 0, 2, "bad_structure", data},
      {"coding 3", 1, 3, "bad_field", data + 1},
      {"reserved", 2, 1, "bad_field", data + 2},
      {"boundary_count", 4, 99, "bad_field", data + 4},
      {"step zero (sign byte of an f32 0x80000000 is -0)", 11, 0x80, "bad_field", data + 8},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    std::vector<uint8_t> bad = good;
    if (c.byte == 11) std::memset(&bad[data + 8], 0, 4);
    bad[data + c.byte] = c.value;
    fix_crc(bad, at);
    const Outcome o = read_outcome(bad);
    CHECK(o.code == c.code);
    CHECK(o.offset == c.offset);
    CHECK(dbss_ref::decode(bad).error == c.code);
  }
}

TEST_CASE("BDRY: placement rules of the table of contents (rule 9)", "[boundary_values]") {
  const auto good = test::build_file(test::jitter(test::planar_grid(5, 4), 0.2f), 2, 30, 0.05f, 1, 0, false, 5);
  format::Reader r = format::read_all(good);
  REQUIRE(r.complete());
  // Body chunks as they are: CTRL, BDRY, LEVL, BDRY, LEVL.
  std::vector<format::RawChunk> body;
  for (const format::TocEntry& e : r.toc())
    body.push_back({e.type, std::vector<uint8_t>(good.begin() + static_cast<long>(e.offset + 8),
                                                 good.begin() + static_cast<long>(e.offset + 8 + e.length))});
  REQUIRE(body.size() == 5);
  REQUIRE(body[1].type == format::kBdry);
  REQUIRE(body[3].type == format::kBdry);
  const std::vector<uint8_t> head = format::encode_header(r.header());
  const auto outcome = [&](std::vector<format::RawChunk> b) {
    const std::vector<uint8_t> file = format::assemble(head, b);
    return std::make_pair(read_outcome(file).code, dbss_ref::decode(file).error);
  };
  CHECK(outcome(body) == std::make_pair(std::string(), std::string()));
  // Two BDRY chunks for one level.
  auto twice = body;
  twice.insert(twice.begin() + 1, body[1]);
  CHECK(outcome(twice) == std::make_pair(std::string("bad_structure"), std::string("bad_structure")));
  // A BDRY after the last LEVL.
  auto after = body;
  after.push_back(body[3]);
  CHECK(outcome(after) == std::make_pair(std::string("bad_structure"), std::string("bad_structure")));
  // A BDRY before CTRL.
  auto before = body;
  std::swap(before[0], before[1]);
  CHECK(outcome(before) == std::make_pair(std::string("bad_structure"), std::string("bad_structure")));
  // Level 2's BDRY moved in front of level 1's LEVL: a second BDRY for level 1.
  auto early = body;
  std::swap(early[2], early[3]);
  CHECK(outcome(early) == std::make_pair(std::string("bad_structure"), std::string("bad_structure")));
}

TEST_CASE("BDRY: a closed mesh has no boundary edge, so a BDRY for it is invalid", "[boundary_values]") {
  const auto good = test::build_file(test::jitter(test::icosahedron(), 0.1f), 1, 30, 0.05f);
  format::Reader r = format::read_all(good);
  REQUIRE(r.complete());
  std::vector<format::RawChunk> body;
  for (const format::TocEntry& e : r.toc())
    body.push_back({e.type, std::vector<uint8_t>(good.begin() + static_cast<long>(e.offset + 8),
                                                 good.begin() + static_cast<long>(e.offset + 8 + e.length))});
  // A BDRY of one value for level 1 (the icosahedron has none).
  format::Level fake;
  fake.index = 1;
  fake.boundary.step = 0.01f;
  fake.boundary.q = {3};
  auto data = format::encode_boundary(fake, 3);
  REQUIRE(data.ok());
  body.insert(body.begin() + 1, format::RawChunk{format::kBdry, data.value()});
  format::Header h = r.header();
  h.version_minor = format::kBoundaryVersionMinor;
  const std::vector<uint8_t> file = format::assemble(format::encode_header(h), body);
  const Outcome o = read_outcome(file);
  CHECK(o.code == "bad_field");
  CHECK(o.offset == format::read_all(file).toc()[1].offset + 8 + 4);
  CHECK(dbss_ref::decode(file).error == "bad_field");
}
