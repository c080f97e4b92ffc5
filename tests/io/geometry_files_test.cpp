// Meshes through every format the io table writes and reads: the same
// triangles come back (as corner coordinates, since STL renumbers), and
// broken faces are refused with the file and the face named.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>

#include "dbss/io/file.h"
#include "dbss/io/geometry_files.h"

using namespace dbss;
namespace fs = std::filesystem;

namespace {

fs::path scratch() {
  const fs::path d = fs::temp_directory_path() / ("dbss-io-test-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

std::string write_text(const std::string& name, const std::string& text) {
  const std::string path = (scratch() / name).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// An octahedron plus one vertex nobody uses (kept by every format but STL).
TriangleMesh octahedron() {
  TriangleMesh m;
  m.positions = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1.5f, 9, 9, 9};
  m.triangles = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  return m;
}

// Each triangle as its three corners' coordinates, rotated so the smallest
// corner comes first (a reader may not renumber, but STL may), sorted.
std::vector<std::array<float, 9>> corner_sets(const TriangleMesh& m) {
  std::vector<std::array<float, 9>> out;
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    std::array<std::array<float, 3>, 3> c;
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) c[k][a] = m.positions[3 * m.triangles[3 * f + k] + a];
    const int first = static_cast<int>(std::min_element(c.begin(), c.end()) - c.begin());
    std::array<float, 9> t;
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) t[3 * k + a] = c[(first + k) % 3][a];
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("every writable format reads back the same triangles") {
  const TriangleMesh m = octahedron();
  for (const char* ext : {"ply", "obj", "off", "stl", "glb", "gltf"}) {
    INFO(ext);
    const std::string path = (scratch() / (std::string("octa.") + ext)).string();
    REQUIRE(write_mesh(path, m).ok());
    auto back = read_mesh(path);
    REQUIRE(back.ok());
    CHECK(back.value().triangle_count() == m.triangle_count());
    CHECK(corner_sets(back.value()) == corner_sets(m));
    // The unused vertex stays, except in STL, which has only corners.
    CHECK(back.value().vertex_count() == (std::string(ext) == "stl" ? 6u : 7u));
  }
}

TEST_CASE("polygons are split into fans and OBJ's relative and slashed corners are read") {
  // A unit square as one quad, then a triangle by negative indices.
  const std::string obj = write_text("quad.obj",
                                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1/1 2//2 3/3 4\nv 0 0 1\nf -1 -5 -4\n");
  auto g = read_geometry(obj);
  REQUIRE(g.ok());
  CHECK(g.value().points.size() == 5);
  CHECK(g.value().triangles == std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 4, 0, 1});
  const std::string off = write_text("quad.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 255 0 0\n");
  auto o = read_geometry(off);
  REQUIRE(o.ok());
  CHECK(o.value().triangles == std::vector<uint32_t>{0, 1, 2, 0, 2, 3});
  // Faces before vertices in a PLY file are fine.
  const std::string ply = write_text("late.ply",
                                     "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_index\n"
                                     "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
                                     "3 2 1 0\n0 0 0\n1 0 0\n0 1 0\n");
  auto p = read_geometry(ply);
  REQUIRE(p.ok());
  CHECK(p.value().triangles == std::vector<uint32_t>{2, 1, 0});
}

TEST_CASE("a point set is not a mesh, and broken faces name the file and the face") {
  const std::string xyz = write_text("pts.xyz", "0 0 0\n1 0 0\n0 1 0\n");
  CHECK(read_points(xyz).ok());
  auto m = read_mesh(xyz);
  REQUIRE_FALSE(m.ok());
  CHECK_THAT(m.status().message(), Catch::Contains("pts.xyz") && Catch::Contains("no faces"));

  struct Case {
    const char* name;
    const char* text;
    const char* says;
  };
  const Case cases[] = {
      {"far.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "line 4"},
      {"zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "bad face corner"},
      {"two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "at least 3 corners"},
      {"far.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "face 0 corner 3"},
      {"two.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "corner count"},
      {"far.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
       "face 0 has corner 7"},
      {"two.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
       "fewer than 3 corners"},
      {"odd.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n",
       "three per facet"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    auto r = read_geometry(write_text(c.name, c.text));
    REQUIRE_FALSE(r.ok());
    CHECK(r.status().code() == ErrorCode::invalid_argument);
    CHECK_THAT(r.status().message(), Catch::Contains(c.name) && Catch::Contains(c.says));
  }
  fs::remove_all(scratch());
}
