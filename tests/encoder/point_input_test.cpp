#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "dbss/encoder/point_input.h"

using namespace dbss;
namespace fs = std::filesystem;

namespace {
const std::vector<float> kPoints = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5f, -2.25f, 3.125f};

fs::path dir() {
  static const fs::path d = [] {
    fs::path p = fs::temp_directory_path() / ("dbss-input-" + std::to_string(::getpid()));
    fs::create_directories(p);
    return p;
  }();
  return d;
}
std::string write(const std::string& name, const std::string& bytes) {
  const fs::path p = dir() / name;
  std::ofstream(p, std::ios::binary) << bytes;
  return p.string();
}
template <class T>
void append(std::string& s, T v, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}
void check_points(const Result<PointCloud>& r) {
  INFO(r.status().to_string());
  REQUIRE(r.ok());
  CHECK(r.value().xyz == kPoints);
}
}  // namespace

TEST_CASE("every supported format reads the same points") {
  std::string xyz, obj = "# comment\no thing\n", off = "OFF\n# a comment\n5 1 0\n";
  for (size_t i = 0; i < 5; ++i) {
    char line[128];
    std::snprintf(line, sizeof line, "%g %g %g", kPoints[3 * i], kPoints[3 * i + 1], kPoints[3 * i + 2]);
    xyz += std::string(line) + " 0 0 1\n";
    obj += "v " + std::string(line) + "\n";
    off += std::string(line) + "\n";
  }
  obj += "f 1 2 3\n";
  off += "3 0 1 2\n";
  check_points(read_points(write("a.xyz", xyz)));
  CHECK(read_points(write("b.xyz", xyz)).value().normals.size() == 15);
  check_points(read_points(write("a.obj", obj)));
  check_points(read_points(write("a.off", off)));

  // PLY: ascii with extra properties and a face list; binary in both byte
  // orders with double coordinates.
  std::string ascii = "ply\nformat ascii 1.0\ncomment x\nelement vertex 5\nproperty float x\nproperty float y\n"
                      "property float z\nproperty uchar red\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (size_t i = 0; i < 5; ++i) {
    char line[128];
    std::snprintf(line, sizeof line, "%g %g %g 255\n", kPoints[3 * i], kPoints[3 * i + 1], kPoints[3 * i + 2]);
    ascii += line;
  }
  ascii += "3 0 1 2\n";
  check_points(read_points(write("a.ply", ascii)));
  for (bool big : {false, true}) {
    std::string ply = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement face 1\nproperty list uchar int vertex_indices\nelement vertex 5\n"
                      "property double x\nproperty double y\nproperty double z\nproperty short extra\nend_header\n";
    append<uint8_t>(ply, 3, big);
    for (int k = 0; k < 3; ++k) append<int32_t>(ply, k, big);
    for (size_t i = 0; i < 5; ++i) {
      for (int a = 0; a < 3; ++a) append<double>(ply, kPoints[3 * i + a], big);
      append<int16_t>(ply, -7, big);
    }
    check_points(read_points(write(big ? "be.ply" : "le.ply", ply)));
  }

  // STL, binary and ascii: the corners of two triangles sharing an edge.
  std::string stl(80, ' ');
  append<uint32_t>(stl, 2, false);
  const float tri[2][9] = {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 0, 1, 0, 0, 0, 1}};
  for (const auto& t : tri) {
    for (int k = 0; k < 3; ++k) append<float>(stl, 0.0f, false);
    for (float x : t) append<float>(stl, x, false);
    append<uint16_t>(stl, 0, false);
  }
  auto b = read_points(write("a.stl", stl));
  REQUIRE(b.ok());
  CHECK(b.value().size() == 4);
  auto a = read_points(write("b.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                                      "endloop\nendfacet\nendsolid s\n"));
  REQUIRE(a.ok());
  CHECK(a.value().size() == 3);
}

TEST_CASE("bad input files give clear errors naming the file and the place") {
  auto err = [](const std::string& name, const std::string& bytes) {
    const std::string path = write(name, bytes);
    auto r = read_points(path);
    REQUIRE(!r.ok());
    CHECK(r.status().message().find(path) != std::string::npos);
    return r.status().message();
  };
  CHECK(err("empty.xyz", "").find("no points") != std::string::npos);
  CHECK(err("nan.xyz", "0 0 0\n1 nan 0\n").find("line 2") != std::string::npos);
  CHECK(err("inf.obj", "v 0 0 0\nv 1 inf 2\n").find("line 2") != std::string::npos);
  CHECK(err("garbage.xyz", "0 0 0\nhello world\n").find("line 2") != std::string::npos);
  CHECK(err("short.xyz", "0 0\n").find("line 1") != std::string::npos);
  CHECK(err("huge.xyz", "1e31 0 0\n").find("line 1") != std::string::npos);
  CHECK(err("cut.off", "OFF\n3 1 0\n0 0 0\n1 1 1\n").find("ends after 2 of 3") != std::string::npos);
  CHECK(err("bad.stl", "not an stl at all").find("STL") != std::string::npos);
  CHECK(err("noheader.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n").find("no 'end_header'") != std::string::npos);
  std::string cut = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  cut += std::string(20, '\0');
  CHECK(err("cut.ply", cut).find("byte") != std::string::npos);
  CHECK(err("x.unknown", "1 2 3\n").find("unknown input format") != std::string::npos);
  // A directory and a missing file: io errors naming the path.
  std::filesystem::create_directories(dir() / "folder.xyz");
  auto d = read_points((dir() / "folder.xyz").string());
  CHECK(d.status().code() == ErrorCode::io);
  CHECK(d.status().message().find("folder.xyz: is a directory") != std::string::npos);
  // A path without an extension is refused before anything is read.
  CHECK(read_points(dir().string()).status().message().find("no file extension") != std::string::npos);
  CHECK(read_points((dir() / "missing.ply").string()).status().code() == ErrorCode::io);
}

TEST_CASE("too few, collinear or coplanar points cannot be reconstructed") {
  PointCloud pc;
  pc.xyz = {0, 0, 0, 1, 1, 1, 2, 2, 2};
  CHECK(check_reconstructible(pc, "p").message().find("at least 4") != std::string::npos);
  pc.xyz = {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3};
  CHECK(check_reconstructible(pc, "p").message().find("line") != std::string::npos);
  pc.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 5, 3, 0};
  CHECK(check_reconstructible(pc, "p").message().find("plane") != std::string::npos);
  pc.xyz = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  CHECK(check_reconstructible(pc, "p").message().find("same point") != std::string::npos);
  // A tetrahedron's corners have volume but are too few for any surface;
  // so are 49 points spread round a sphere; 50 are enough.
  pc.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  CHECK(check_reconstructible(pc, "p").message().find("p: has 4 points; reconstructing a surface needs at least 50") !=
        std::string::npos);
  const auto sphere = [](size_t n) {
    PointCloud c;
    for (size_t i = 0; i < n; ++i) {
      // A Fibonacci spiral: evenly spread, no two points alike.
      const double z = 1 - (2 * static_cast<double>(i) + 1) / static_cast<double>(n);
      const double a = 2.399963 * static_cast<double>(i), r = std::sqrt(1 - z * z);
      c.xyz.insert(c.xyz.end(), {static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), static_cast<float>(z)});
    }
    return c;
  };
  CHECK(check_reconstructible(sphere(kMinReconstructPoints - 1), "p").message().find("at least 50") != std::string::npos);
  pc = sphere(kMinReconstructPoints);
  CHECK(check_reconstructible(pc, "p").ok());
  // Points handed over in memory get the file readers' coordinate bound.
  pc.xyz[7] = 1e20f;
  CHECK(check_reconstructible(pc, "p").message().find("point 2 has a coordinate that is NaN, infinite or over 1e15") !=
        std::string::npos);
}
