// The indexed triangle mesh every dbss stage hands around.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace dbss {

struct TriangleMesh {
  std::vector<float> positions;      // x, y, z per vertex, model units
  std::vector<uint32_t> triangles;   // three vertex indices per triangle, counter-clockwise seen from outside
  std::size_t vertex_count() const noexcept { return positions.size() / 3; }
  std::size_t triangle_count() const noexcept { return triangles.size() / 3; }
  friend bool operator==(const TriangleMesh&, const TriangleMesh&) = default;
};

}  // namespace dbss
