// Exact distances between a point set and a triangle mesh's surface, for
// error figures (`dbss compare`, benchmarks, tests).  Not on any decoding
// path.
#pragma once

#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/point_index.h"

namespace dbss {

// Squared distance from p to the closest point of triangle abc (any shape,
// degenerate included), in binary64.
double point_triangle_distance2(const double p[3], const double a[3], const double b[3], const double c[3]);

// A bounding-volume hierarchy over a mesh's triangles for exact
// closest-surface queries.  Keeps its own copy of the triangles' corners.
class TriangleTree {
 public:
  explicit TriangleTree(const TriangleMesh& mesh);
  // Distance from p to the closest point of the surface (infinity for a mesh
  // without triangles).
  double distance(const double p[3]) const;
  size_t triangle_count() const noexcept { return corners_.size() / 9; }

 private:
  struct Node {
    double lo[3], hi[3];
    uint32_t first, count;  // leaf: triangles [first, first + count); inner: count == 0, children first, first + 1
  };
  std::vector<double> corners_;  // 9 per triangle, in tree order
  std::vector<Node> nodes_;
};

// Both directions between the points and a mesh, in model units:
// points -> mesh is each point's exact distance to the surface; mesh ->
// points samples the surface (every triangle on a barycentric grid no
// coarser than the points' median spacing) and takes each sample's distance
// to the nearest point, area-weighted.  The second direction therefore has a
// floor of about half the point spacing even on a perfect surface.
struct TwoSidedDistance {
  double points_to_mesh_mean = 0, points_to_mesh_max = 0;
  double mesh_to_points_mean = 0, mesh_to_points_max = 0;
  double mean() const noexcept { return 0.5 * (points_to_mesh_mean + mesh_to_points_mean); }
  double hausdorff() const noexcept { return points_to_mesh_max > mesh_to_points_max ? points_to_mesh_max : mesh_to_points_max; }
};
TwoSidedDistance two_sided_distance(const PointIndex& points, const TriangleMesh& mesh);

}  // namespace dbss
