// Points from binary PLY (issue 19: scans of millions of points come as
// binary PLY): both byte orders, float and double coordinates, other
// properties between them skipped, and a file cut short refused.
#include <catch2/catch.hpp>

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "dbss/io/geometry_files.h"

using namespace dbss;

namespace {

template <class T>
void put(std::string& out, T value, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  // The host is little-endian on every platform the project builds for.
  static_assert(std::endian::native == std::endian::little);
  if (big)
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  out.append(b, sizeof(T));
}

const std::vector<std::array<double, 3>> kPoints = {{0.5, -1.25, 3.0}, {1e-3, 2.5e6, -7.75}, {-0.0, 0.125, 1.0 / 3}};

// x, y, z of type T with a uchar and an int property between y and z.
template <class T>
std::string ply(bool big, const char* type) {
  std::string s = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\nelement vertex 3\nproperty " + type + " x\nproperty " + type +
                  " y\nproperty uchar red\nproperty int id\nproperty " + type + " z\nend_header\n";
  int id = 0;
  for (const auto& p : kPoints) {
    put<T>(s, static_cast<T>(p[0]), big);
    put<T>(s, static_cast<T>(p[1]), big);
    put<uint8_t>(s, 200, big);
    put<int32_t>(s, id++, big);
    put<T>(s, static_cast<T>(p[2]), big);
  }
  return s;
}

}  // namespace

TEST_CASE("binary PLY points: both byte orders, float and double, other properties skipped") {
  for (bool big : {false, true})
    for (bool dbl : {false, true}) {
      INFO((big ? "big endian " : "little endian ") << (dbl ? "double" : "float"));
      const std::string bytes = dbl ? ply<double>(big, "double") : ply<float>(big, "float");
      auto r = parse_points("scan.ply", bytes);
      INFO(r.status().to_string());
      REQUIRE(r.ok());
      REQUIRE(r.value().size() == kPoints.size());
      for (size_t i = 0; i < kPoints.size(); ++i)
        for (int a = 0; a < 3; ++a) {
          const float want = dbl ? static_cast<float>(kPoints[i][a]) : static_cast<float>(static_cast<float>(kPoints[i][a]));
          CHECK(r.value().xyz[3 * i + a] == want);
        }
      // Cut inside the last point: refused, naming the file.
      auto cut = parse_points("scan.ply", std::string_view(bytes).substr(0, bytes.size() - 3));
      REQUIRE(!cut.ok());
      CHECK(cut.status().to_string().find("scan.ply") != std::string::npos);
    }
}
