// Open surfaces (a scan seen from one side, a patch of an object): the
// carved shell of a sheet of points is a thin closed slab whose two sides
// both lie on the points.  These steps keep one side and give the surface a
// boundary where the points end.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/cell_carving.h"
#include "dbss/encoder/point_index.h"

namespace dbss {

// Unit point normals from the least-squares plane of each point's k nearest
// points, oriented consistently along a minimum spanning tree of the
// k-nearest-neighbour graph (edges cost 1 - |n_i . n_j|, so orientation is
// passed across flat, well-sampled regions first), then each cluster of the
// tree flipped so most normals point away from its centroid.
std::vector<std::array<float, 3>> oriented_normals(const PointIndex& index, size_t k = 12);

struct SheetCut {
  TriangleMesh sheet;     // the kept side, an oriented manifold with boundary (vertices renumbered)
  size_t removed = 0;     // shell triangles removed
  // Of those, the ones behind the points (their centroid more than a
  // quarter of an edge on the far side of the nearest point, along its
  // oriented normal): the inside of a slab or of a leak.  A closed shell
  // whose noisy normals flip a few triangles has them in front.
  size_t behind = 0;
};

// Per shell triangle, whether the solid under it is thin: walking from the
// triangle into the solid along its inward normal reaches air within
// `cells` cells without meeting an empty inside cell (a slab, or a thin
// part).  `shell` must be `grid`'s triangulated shell.
std::vector<uint8_t> thin_under(const TriangleMesh& shell, const CellGrid& grid, int cells = 4);

// Keeps the shell triangles whose outward normal agrees with the oriented
// normal of the nearest point, then cleans the choice up: kept islands under
// 1% of the kept triangles go, dropped islands under 1% that only kept
// triangles surround come back, triangles with two or three boundary edges
// go, and at a vertex where the kept triangles form several fans only the
// largest fan stays.  `shell` must be a closed oriented manifold.
// `thin` (optional, per shell triangle): `behind` counts only triangles
// over thin solid, so a thick closed object whose normals flipped in a
// patch (noise) shows none.
SheetCut cut_to_sheet(const TriangleMesh& shell, const PointIndex& index, const std::vector<std::array<float, 3>>& normals,
                      const std::vector<uint8_t>* thin = nullptr);

// Removes triangles whose three corners and centroid are all farther than
// `reach` from every point (the rim of the slab overhanging the points),
// then the same clean-up as cut_to_sheet.  Returns how many went.
size_t trim_unsupported(TriangleMesh& sheet, const PointIndex& index, double reach);

// Boundary loops of an oriented manifold, each as its vertices in the order
// of the boundary half-edges (the triangle on the left of the walk).
std::vector<std::vector<uint32_t>> boundary_loops(const TriangleMesh& m);

struct HoleFill {
  size_t loops = 0;            // holes closed (a bridged pair counts two)
  size_t bridges = 0;          // pairs of loops joined by a tube
  size_t doubtful_pairs = 0;   // with `bridge`: pairs capped that half looked like a cut tube's ends
  size_t triangles = 0;        // triangles added
  double area = 0;             // their area, model units^2
  std::vector<uint32_t> added_vertices;  // the new vertices (no points support them)
  // With `bridge`: the tubes' triangles, three corners each (xyz, a soup),
  // where they were built: the self-check tells the encoder's own handles
  // from bare ones by place (scan_check.cpp).
  std::vector<float> bridge_triangles;
};

// Closes every boundary loop shorter than `max_perimeter` (model units)
// with a patch: concentric rings about two `edge`s apart from the loop
// towards its centroid, the innermost closed by a zig-zag strip; the new
// vertices relax to a membrane (the loop held still), then are faired so
// the patch's slope follows the surface around the hole.  The result keeps
// the orientation.  With `bridge`, loops that face each other across a gap
// (the two ends of a tube the scan cut through) are first joined by a tube
// (hole_bridge.h), which is faired with the patches.
HoleFill fill_holes(TriangleMesh& m, double edge, double max_perimeter = 1e300, bool bridge = false);

// Length of a closed loop of vertices, model units.
double loop_perimeter(const TriangleMesh& m, const std::vector<uint32_t>& loop);

// Area of triangle t, and of the whole mesh; model units^2.
double triangle_area(const TriangleMesh& m, size_t t);
double mesh_area(const TriangleMesh& m);

}  // namespace dbss
