// The grid search may keep its chosen grid moved by half a cell (a handle
// only one placement of the cells shows, cell_carving.cpp).  `meta` records
// the grid as grid=N and that move as grid-shift=S, and re-encoding with
// --grid N --grid-shift S (ControlMeshOptions::grid, grid_shift) must give
// the same file byte for byte: a file says how to make it again.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <string>

#include "dbss/encoder/encode.h"
#include "../crease_shapes.h"
#include "../defect_shapes.h"
#include "../sampled_shapes.h"

using namespace dbss;
namespace dt = dbss::test;

namespace {

std::string params(const Encoding& e) {
  for (const auto& m : e.contents.metadata)
    if (m.key == "encoder.params") return m.value;
  return "";
}

// The value after "key=" in encoder.params ("" when absent).
std::string param(const std::string& p, const std::string& key) {
  const std::string k = key + "=";
  size_t at = p.find(k);
  while (at != std::string::npos && at != 0 && p[at - 1] != ' ') at = p.find(k, at + 1);
  if (at == std::string::npos) return "";
  const size_t from = at + k.size();
  return p.substr(from, p.find(' ', from) - from);
}

}  // namespace

TEST_CASE("grid shift: meta records the search's half-cell move, and --grid N --grid-shift S reproduces the file") {
  // The sparse triple torus whose grid search keeps its grid moved by half
  // a cell (control_mesh_test's case): carved in place it bores a fourth
  // handle.
  const dt::Shape& s = dt::genus_shape("triple torus");
  const PointCloud pc = dt::sample_sdf(s.sdf, s.lo, s.hi, 5000, 7);
  EncodeOptions o;
  o.levels = 1;
  auto a = encode_points(pc, o);
  REQUIRE(a.ok());
  REQUIRE(a.value().stages.carving.shift == 0.5);
  const std::string p = params(a.value());
  INFO("encoder.params: " << p);
  CHECK(param(p, "grid-shift") == "0.5");
  const int grid = std::atoi(param(p, "grid").c_str());
  REQUIRE(grid == a.value().stages.carving.grid);

  // The recorded options again: the same bytes.
  EncodeOptions given = o;
  given.control.grid = grid;
  given.control.grid_shift = std::atof(param(p, "grid-shift").c_str());
  auto b = encode_points(pc, given);
  REQUIRE(b.ok());
  CHECK(params(b.value()) == p);
  CHECK(b.value().bytes == a.value().bytes);

  // The grid alone is another carving (the shift is what was missing):
  // its fourth handle, and other bytes.
  EncodeOptions unshifted = o;
  unshifted.control.grid = grid;
  auto c = encode_points(pc, unshifted);
  REQUIRE(c.ok());
  CHECK(param(params(c.value()), "grid-shift").empty());
  CHECK(c.value().bytes != a.value().bytes);
}

TEST_CASE("grid shift: an unshifted choice writes no grid-shift, and its grid alone reproduces the file") {
  const dt::Shape& s = dt::genus_shape("torus");
  const PointCloud pc = dt::sample_sdf(s.sdf, s.lo, s.hi, 3000, 7);
  EncodeOptions o;
  o.levels = 1;
  auto a = encode_points(pc, o);
  REQUIRE(a.ok());
  REQUIRE(a.value().stages.carving.shift == 0);
  const std::string p = params(a.value());
  INFO("encoder.params: " << p);
  CHECK(p.find("grid-shift") == std::string::npos);
  EncodeOptions given = o;
  given.control.grid = std::atoi(param(p, "grid").c_str());
  auto b = encode_points(pc, given);
  REQUIRE(b.ok());
  CHECK(b.value().bytes == a.value().bytes);
}

TEST_CASE("control-faces in encoder.params is the count QEM was asked for: a tagged file with collapses is made again by it") {
  // Creases collapse short edges and flip slivers after QEM
  // (crease_short_edges.cpp), so the file's control mesh has fewer faces
  // than QEM made.  Recording that final count built a different mesh when
  // given back; the request is what reproduces the file.
  const PointCloud pc = test::sampled(test::cube(), 8000, 1);
  EncodeOptions o = test::crease_options(30, 1);
  auto a = encode_points(pc, o);
  REQUIRE(a.ok());
  REQUIRE(a.value().creases.creases > 0);
  REQUIRE(a.value().creases.short_collapses > 0);
  REQUIRE(a.value().control.triangle_count() != a.value().stages.target_faces);
  const std::string p = params(a.value());
  INFO("encoder.params: " << p);
  const int faces = std::atoi(param(p, "control-faces").c_str());
  CHECK(faces == static_cast<int>(a.value().stages.target_faces));

  EncodeOptions given = o;
  given.control.grid = std::atoi(param(p, "grid").c_str());
  given.control.control_faces = static_cast<uint32_t>(faces);
  given.control_bits = std::atoi(param(p, "control-bits").c_str());
  auto b = encode_points(pc, given);
  REQUIRE(b.ok());
  // The same surface at every level (meta differs: no face choice ran).
  CHECK(b.value().control.triangle_count() == a.value().control.triangle_count());
  CHECK(b.value().control.positions == a.value().control.positions);
  CHECK(b.value().levels.positions == a.value().levels.positions);
  CHECK(b.value().contents.level_data == a.value().contents.level_data);
}
