// Control-mesh shaping after QEM: edge flips toward valence 6 and away from
// slivers, and a tangential relaxation of the vertices around slivers that
// keeps them on the points.  The Modified Butterfly's extraordinary-vertex
// stencils overshoot around slivers and high valences (a fan of ripples on
// a flat face at level 1), and the vertex normals that carry the
// displacements swing with them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_set>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/point_index.h"

namespace dbss {

// Triangle shape quality 4*sqrt(3)*area / (sum of squared edge lengths):
// 1 for an equilateral triangle, 0 for a degenerate one.
double triangle_quality(const TriangleMesh& m, size_t triangle);

// The figures shaping is judged by.
struct MeshShape {
  double poor_share = 0;     // share of triangles with quality under kPoorQuality
  double min_quality = 0;    // the worst triangle's
  uint32_t max_valence = 0;  // the most edges at one vertex
};
inline constexpr double kPoorQuality = 0.2;
MeshShape mesh_shape(const TriangleMesh& m);

struct ShapeOptions {
  bool enabled = true;
  int rounds = 6;  // flip passes, each followed by a relaxation
  // Degrees between a vertex's normal and one of its triangles' above
  // which the vertex is never moved, and between the normals of an edge's
  // two triangles above which it is never flipped when no points are
  // given: sharp features stay where QEM put them.
  double max_bend = 25;
  // The flips' limit when points are given: then a flip must also keep the
  // surface on the points (its new edge's midpoint no farther from them
  // than the old one's, plus flip_slack median point spacings; slack lets
  // the surface drift: on the eight 0.5 took every level 2-15% farther from
  // the truth than 0),
  // which is what tells a crease, where the new edge would cut the corner,
  // from the bend of a coarse mesh on a curved surface (45 degrees around a
  // thin tube).
  double flip_bend = 45;
  double flip_slack = 0;
  // Vertices of triangles under this quality are relaxed (the rest keep
  // QEM's placement, which follows curvature); 0: flips only.  At 0.4 the
  // creased fandisk's level 3 came out twice as close as at 0.2 (2.2e-4
  // against 4.3e-4 of the diagonal, 1.6e-3 unshaped), but a sphere's level
  // 0 and 1 were 53% and 10% farther than unshaped (0.2: 13% and 1%).
  double relax_below = 0.2;
  // Relaxed vertices move onto points only: the one of the 8 nearest to
  // the relaxed position that gives the vertex's triangles the best worst
  // quality, if better than now (for a mesh already on the points; the
  // jumps of projection leave slivers next to short edges).
  bool snap = false;
};

struct ShapeStats {
  MeshShape before, after;  // the mesh handed in, the mesh handed back
  size_t flips = 0;       // edges flipped
  size_t moves = 0;       // vertex moves kept by the relaxation
  size_t rounds_undone = 0;  // rounds thrown away because triangles crossed
};

// Improves `mesh` in place (an oriented manifold, closed or with boundary)
// in up to `rounds` rounds of:
//  - flips of interior edges that lower the valence excess
//    sum((valence - 6)^2) (4 on the boundary) of their four vertices
//    without making a sliver, or raise the worse of their two triangles'
//    quality when it is poor; never when the edge's two triangles or the
//    flipped pair bend by more than max_bend (flip_bend with points), nor
//    when the new edge's midpoint lies farther from the points than the
//    old one's (see flip_slack), nor when the new edge exists already
//    (which would make a non-manifold edge), nor below valence 3 or above
//    valence 10;
//  - moves of each interior vertex of a triangle under relax_below quality
//    half way toward its neighbours' mean, within its tangent plane, then
//    onto the least-squares plane of its 8 nearest points, or onto one of
//    those points (`snap`, or where that plane leans more than max_bend
//    from the vertex normal; `points` null: the move stays in the tangent
//    plane).  A move that turns a triangle over or folds an edge is not
//    made; boundary vertices and vertices on sharp features (a triangle
//    more than max_bend from the vertex normal) never move.
// Topology (genus, components, boundary loops) is unchanged by
// construction; a round after which more triangle pairs cross than before
// the pass is undone and ends the pass.  Deterministic (a fixed visiting
// order).
ShapeStats improve_shape(TriangleMesh& mesh, const PointIndex* points, const ShapeOptions& options = {});

// What a shaping pass must leave alone (a tagged control mesh's lines):
// vertices that never move (pinned[v] != 0; empty: none) and undirected
// edges that are never flipped (mesh_geometry.h's edge_key of their ends).
struct ShapeLocks {
  std::vector<uint8_t> pinned;
  std::unordered_set<uint64_t> kept_edges;
  // Flips held at vertices (empty: none): a flip with one of its four
  // corners at 1 (on a tagged line) is made only when the worse of its two
  // triangles gets no worse; with one at 2 (at an untagged edge that bends
  // sharply: a gap in a line) it is not made.
  std::vector<uint8_t> beside;
};
// improve_shape with `locks`: as above, and no pinned vertex moves and no
// kept edge is flipped (a kept edge stays an edge: a flip only removes the
// edge it flips).
ShapeStats improve_shape(TriangleMesh& mesh, const PointIndex* points, const ShapeOptions& options, const ShapeLocks& locks);

}  // namespace dbss
