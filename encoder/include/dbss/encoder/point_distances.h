// Where points lie relative to a surface: exact distances to a mesh, the
// local least-squares plane of points, and the inside test of a closed mesh.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/point_index.h"

namespace dbss {

// Mean and largest exact distance from each point to the mesh's surface
// (through surface_distance.h's TriangleTree).
struct SurfaceDistance {
  double mean = 0, max = 0;
};
SurfaceDistance points_to_mesh(const std::vector<float>& points_xyz, const TriangleMesh& mesh);

// The least-squares plane of points `indices[0..count)`: their centroid and
// the unit normal of least spread (sign arbitrary; zero for count 0).
struct PointPlane {
  std::array<double, 3> point{}, normal{};
  // The points' variances along the plane's normal and its two in-plane
  // axes, ascending: the middle one near zero means the points lie on a
  // line and the plane through them is arbitrary.
  std::array<double, 3> variance{};
};
PointPlane fit_plane(const PointCloud& points, const uint32_t* indices, size_t count);

// Mean and largest distance from each vertex to the surface of the points,
// taken as the least-squares plane of its 8 nearest points.
SurfaceDistance vertices_to_points_surface(const std::vector<float>& vertices_xyz, const PointIndex& points);

// Winding-number inside test of a closed, outward-oriented mesh.
bool inside_mesh(const TriangleMesh& m, const std::array<double, 3>& p);

}  // namespace dbss
