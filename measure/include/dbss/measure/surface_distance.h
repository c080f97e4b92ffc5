// Exact distances between a point set and a triangle mesh's surface, for
// error figures (`dbss compare`, benchmarks, tests).  Not on any decoding
// path.
#pragma once

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/triangle_tree.h"

namespace dbss {

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
