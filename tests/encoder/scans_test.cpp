// The libcgal-demo scans end to end (skipped when scripts/fetch-test-data.sh
// has not unpacked them, failed instead under CI=true; ../test_data.h):
// encode, decode every level from the file's bytes, compare bit for bit,
// and hold the quality targets.
#include <catch2/catch.hpp>

#include <cstring>
#include <string>

#include "../test_data.h"

#include "dbss/decoder/progressive.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/point_distances.h"
#include "dbss/encoder/shell_mesh.h"
#include "dbss/measure/surface_distance.h"

using namespace dbss;

namespace {
void encode_scan(const char* relative, int64_t genus, double max_mean) {
  const auto path = test::scan_data(relative);
  if (!path) return;
  INFO(*path);
  auto pc = read_points(*path);
  REQUIRE(pc.ok());
  EncodeOptions o;
  o.levels = 3;
  auto e = encode_points(pc.value(), o);
  REQUIRE(e.ok());
  const Encoding& enc = e.value();
  const MeshInfo info = mesh_info(enc.control);
  CHECK(info.closed);
  CHECK(info.components == 1);
  CHECK(info.genus == genus);
  const PointIndex index(pc.value());
  for (uint32_t l = 0; l <= 3; ++l) {
    INFO("level " << l);
    auto m = decode_bytes(enc.bytes, static_cast<int>(l));
    REQUIRE(m.ok());
    REQUIRE(m.value().positions.size() == enc.levels.positions[l].size());
    CHECK(std::memcmp(m.value().positions.data(), enc.levels.positions[l].data(), 4 * m.value().positions.size()) == 0);
    CHECK(m.value().triangles == enc.levels.triangles[l]);
    if (l == 0) continue;
    CHECK(enc.levels.stats[l - 1].clamped * 100 < enc.levels.stats[l - 1].odd);
  }
  // Mean two-sided distance at level 3: the points' exact distance to the
  // surface, and the vertices' distance to the points' surface (their 8
  // nearest points' plane; a nearest-point distance would measure the
  // sampling gaps, not the surface).
  const TriangleMesh finest{enc.levels.positions[3], enc.levels.triangles[3]};
  const double to_surface = two_sided_distance(index, finest).points_to_mesh_mean;
  const double to_points = vertices_to_points_surface(finest.positions, index).mean;
  CHECK(0.5 * (to_surface + to_points) < max_mean * enc.diagonal);
}
}  // namespace

TEST_CASE("bunny scan: genus 0, bit-exact levels, level 3 within 0.1% of the diagonal, under 1% clamped") {
  encode_scan("data/meshes/bunny00.off", 0, 1e-3);
}

TEST_CASE("kitten scan: genus 1, bit-exact levels, level 3 within 0.1% of the diagonal, under 1% clamped") {
  encode_scan("data/points_3/kitten.xyz", 1, 1e-3);
}
