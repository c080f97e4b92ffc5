// Mesh input: a triangle mesh (an artist's or a photogrammetry tool's) as
// the surface to encode, instead of points to reconstruct one from.  The
// input's own triangles are the true surface: the control mesh is
// simplified from them and every displacement is cast against them.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/mesh_info.h"
#include "dbss/encoder/sampling.h"
#include "dbss/encoder/triangle_tree.h"
#include "dbss/format/status.h"

namespace dbss {

struct MeshCleanup {
  size_t degenerate_triangles = 0;  // with a repeated corner, dropped
  size_t unused_vertices = 0;       // on no triangle, dropped
};

// The input made ready for encoding: triangles with a repeated corner and
// vertices on no triangle dropped (vertices renumbered in their order).
// Refuses (invalid_argument, naming the first offending edge or vertex in
// the input's own numbering) a mesh that is not an oriented 2-manifold:
// an edge in three or more triangles, an edge two triangles use in the same
// direction (inconsistent orientation), a vertex whose triangles form more
// than one fan (a bow-tie).  Such a mesh is never encoded: the format's
// subdivision is defined on manifolds only.  Valence is not limited here
// (the simplified control mesh is checked by build_topology).
Result<TriangleMesh> prepare_mesh_input(const TriangleMesh& mesh, MeshCleanup* cleanup = nullptr);

// The input surface for sampling: a bounding-volume hierarchy over its
// triangles and one over its boundary edges.  Safe to query from several
// threads at once.
class MeshSurface {
 public:
  explicit MeshSurface(const TriangleMesh& mesh);
  // The displacement of an odd vertex at p with unit normal n: the nearest
  // crossing of the line p + t n with the input triangles within
  // |t| <= half_length (facing triangles first, see
  // TriangleTree::nearest_line_hit), source `triangle`; when the line
  // misses, the offset along n of the closest surface point, source
  // `nearest`, clamped to half_length.  An odd vertex on a boundary edge
  // (`boundary`) takes the offset along n of the closest point of the
  // input's boundary curve instead, so the levels' boundaries follow the
  // input's (a normal displacement cannot move it along the surface; this
  // is the nearest it gets).
  // With `tangent` (a unit vector along the odd vertex's boundary edge),
  // the boundary point taken is where the curve crosses the plane through
  // p perpendicular to it (boundary_target), the point a vertex moving
  // along its normal and across the boundary can reach.
  Sample sample(const double p[3], const double n[3], double half_length, bool boundary,
                const double* tangent = nullptr) const;
  // The point of the input's boundary curve in the plane through p
  // perpendicular to the unit vector t (near p): from p's closest boundary
  // point, a few steps of projecting onto the plane and back onto the curve.
  void boundary_target(const double p[3], const double t[3], double out[3]) const;
  // The closest point of the surface, or of its boundary curve (p itself
  // when the input has no boundary); both return the distance.
  double closest_point(const double p[3], double out[3]) const { return surface_.closest_point(p, out); }
  double closest_boundary_point(const double p[3], double out[3]) const;
  // Format 1.3: the offset along the unit in-surface direction b from m
  // (unit normal n) to the boundary curve's point in m's plane across the
  // edge (boundary_target with t = n x b), clamped to half_length (0 when
  // the input has no boundary).
  double boundary_offset(const double m[3], const double b[3], const double n[3], double half_length) const;
  bool has_boundary() const noexcept { return rim_.triangle_count() > 0; }

 private:
  TriangleTree surface_;
  TriangleTree rim_;  // boundary edges as degenerate triangles (a, b, b)
};

// Per edge of a level's mesh in the canonical order (the odd vertices of
// the next level): 1 when the edge is on the boundary.  Empty when the mesh
// is not a manifold (not reachable for a level a refiner made).
std::vector<uint8_t> boundary_edges(uint32_t vertex_count, std::span<const uint32_t> triangles);

struct MeshControlStats {
  uint32_t faces_before = 0, faces_after = 0;
  size_t boundary_vertices = 0;  // of the control mesh, put on the input's boundary curve
};

// The control mesh of a prepared input: QEM-simplified to `target_faces`
// (simplify_mesh: genus, components and boundary loops kept), then every
// vertex put on the input surface (its closest point; boundary vertices:
// the closest point of the boundary curve).  Fails with internal when the
// result's topology differs from the input's (a bug).
Result<TriangleMesh> control_mesh_from_mesh(const TriangleMesh& input, const MeshSurface& surface,
                                            uint32_t target_faces, MeshControlStats* stats = nullptr);

// The QEM needle limit (SimplifyOptions::needle) control_mesh_from_mesh
// uses: 0.01 when the input has more than 32 times `target_faces`
// triangles, 0.05 (the simplifier's default) otherwise.
double mesh_control_needle(size_t input_faces, uint32_t target_faces);

}  // namespace dbss
