#include <catch2/catch.hpp>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include <algorithm>
#include <array>
#include <set>

#include "../shapes.h"
#include "dbss/decoder/control_mesh.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/control_mesh_codec.h"

using dbss::TriangleMesh;

namespace {

// Triangles as sets of rounded positions, so two meshes compare without
// depending on vertex numbering or on where a triangle's corners start.
std::multiset<std::array<std::array<long, 3>, 3>> geometric_triangles(const TriangleMesh& m, double cell) {
  std::multiset<std::array<std::array<long, 3>, 3>> out;
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    std::array<std::array<long, 3>, 3> t;
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) t[k][a] = std::lround(m.positions[3 * m.triangles[3 * f + k] + a] / cell);
    // Rotate so the smallest corner comes first; keeps orientation.
    const auto first = std::min_element(t.begin(), t.end()) - t.begin();
    std::rotate(t.begin(), t.begin() + first, t.end());
    out.insert(t);
  }
  return out;
}

}  // namespace

TEST_CASE("Draco control mesh round trip keeps counts, positions within quantization, and triangles") {
  const TriangleMesh in = dbss::test::torus(10, 5);
  for (int bits : {11, 14, 16, 20}) {
    INFO("position bits " << bits);
    auto bytes = dbss::encode_control_mesh(in, {bits, 0});
    REQUIRE(bytes.ok());
    auto out = dbss::decode_control_mesh(bytes.value(), 1000, 1000);
    REQUIRE(out.ok());
    const TriangleMesh& m = out.value();
    CHECK(m.vertex_count() == 50);
    CHECK(m.triangle_count() == 100);
    // Every decoded vertex is within half a quantization step of an input vertex.
    const double range = 2 * 1.4;
    const double tol = range / ((1 << bits) - 1) * 0.5 * std::sqrt(3.0) + 1e-6;
    for (size_t v = 0; v < m.vertex_count(); ++v) {
      double best = 1e9;
      for (size_t w = 0; w < in.vertex_count(); ++w) {
        double d2 = 0;
        for (int a = 0; a < 3; ++a) d2 += std::pow(m.positions[3 * v + a] - in.positions[3 * w + a], 2);
        best = std::min(best, std::sqrt(d2));
      }
      REQUIRE(best <= tol);
    }
    // Same oriented triangles, compared by position on a grid far coarser
    // than the quantization step (and far finer than the edge length).
    if (bits >= 14) CHECK(geometric_triangles(m, 0.05) == geometric_triangles(in, 0.05));
  }
}

TEST_CASE("Draco decode is deterministic: same bytes, same mesh") {
  auto bytes = dbss::encode_control_mesh(dbss::test::torus(12, 6), {});
  REQUIRE(bytes.ok());
  auto a = dbss::decode_control_mesh(bytes.value(), 1000, 1000);
  auto b = dbss::decode_control_mesh(bytes.value(), 1000, 1000);
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  CHECK(a.value() == b.value());
}

TEST_CASE("control mesh decoding refuses limits, garbage and every truncation without crashing") {
  auto bytes = dbss::encode_control_mesh(dbss::test::torus(10, 5), {});
  REQUIRE(bytes.ok());
  const auto& b = bytes.value();
  CHECK(dbss::decode_control_mesh(b, 49, 1000).status().code() == dbss::ErrorCode::limit_exceeded);
  CHECK(dbss::decode_control_mesh(b, 1000, 99).status().code() == dbss::ErrorCode::limit_exceeded);
  const std::vector<uint8_t> garbage(100, 0xAB);
  CHECK(!dbss::decode_control_mesh(garbage, 1000, 1000).ok());
  CHECK(!dbss::decode_control_mesh({}, 1000, 1000).ok());
  size_t failures = 0;
  for (size_t n = 0; n < b.size(); ++n) {
    auto r = dbss::decode_control_mesh(std::span<const uint8_t>(b.data(), n), 1000, 1000);
    if (!r.ok()) ++failures;
  }
  // Draco has no checksum, so a cut could still decode to something (the
  // container's CRC is what catches damage), but measured, every one of
  // the 382 cuts of this mesh fails outright: so must they all.
  CHECK(failures == b.size());
}

TEST_CASE("encode_control_mesh rejects malformed meshes") {
  TriangleMesh m = dbss::test::torus(4, 3);
  m.triangles[5] = 1000;
  CHECK(dbss::encode_control_mesh(m).status().code() == dbss::ErrorCode::invalid_argument);
  TriangleMesh empty;
  CHECK(!dbss::encode_control_mesh(empty).ok());
  CHECK(dbss::encode_control_mesh(dbss::test::torus(4, 3), {40, 0}).status().code() ==
        dbss::ErrorCode::invalid_argument);
}

TEST_CASE("Draco's points split by a second attribute merge back into one vertex per position") {
  // Per-face normals make Draco keep several points at each corner
  // position; the decoder must give one vertex per position value, or the
  // mesh would fall apart into separate triangles.
  const dbss::TriangleMesh m = dbss::test::bipyramid(5);
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(static_cast<int>(m.triangle_count()));
  const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int nrm = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    const float* p[3];
    for (int k = 0; k < 3; ++k) p[k] = &m.positions[3 * size_t{m.triangles[3 * f + k]}];
    const float u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const float w[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const float n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const draco::FaceIndex fi(static_cast<uint32_t>(f));
    builder.SetAttributeValuesForFace(pos, fi, p[0], p[1], p[2]);
    builder.SetAttributeValuesForFace(nrm, fi, n, n, n);
  }
  auto mesh = builder.Finalize();
  REQUIRE(mesh);
  REQUIRE(mesh->num_points() > m.vertex_count());  // the split really happened
  draco::Encoder enc;
  enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 16);
  enc.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 8);
  draco::EncoderBuffer out;
  REQUIRE(enc.EncodeMeshToBuffer(*mesh, &out).ok());
  auto back = dbss::decode_control_mesh({reinterpret_cast<const uint8_t*>(out.data()), out.size()}, 1 << 20, 1 << 20);
  INFO(back.status().to_string());
  REQUIRE(back.ok());
  CHECK(back.value().vertex_count() == m.vertex_count());
  CHECK(back.value().triangle_count() == m.triangle_count());
  CHECK(dbss::build_topology(static_cast<uint32_t>(back.value().vertex_count()), back.value().triangles).ok());
}
