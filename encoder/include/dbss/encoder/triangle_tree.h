// Exact distance from a point to a triangle mesh's surface: a bounding-volume
// hierarchy over its triangles.  Reconstruction uses it to tell how far
// points lie from a candidate surface; the measuring library
// (dbss/measure) builds its error figures on it.
#pragma once

#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"

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
  // The closest point of the surface to p, written to `out` (p itself for a
  // mesh without triangles); returns its distance.
  double closest_point(const double p[3], double out[3]) const;
  // Where the line p + t * dir (dir of unit length) crosses the surface
  // within |t| <= limit: the crossing of least |t|, preferring triangles
  // that face the same way as dir (dot of their normal with dir > 0) over
  // those facing away, so a line from a thin part's outside takes its near
  // sheet.  Returns false when the line meets no triangle there.
  bool nearest_line_hit(const double p[3], const double dir[3], double limit, double& t) const;

 private:
  struct Node {
    double lo[3], hi[3];
    uint32_t first, count;  // leaf: triangles [first, first + count); inner: count == 0, children first, first + 1
  };
  std::vector<double> corners_;  // 9 per triangle, in tree order
  std::vector<Node> nodes_;
};

}  // namespace dbss
