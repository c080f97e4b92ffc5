// Triangles that turn over: whether a vertex move flips its fan, which
// edges are folded, and smoothing that takes folds away.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/mesh_adjacency.h"

namespace dbss {

// Whether moving vertex v to `to` keeps every triangle around it facing
// within 90 degrees of where it faced before (no triangle turns over).
// Meshes with boundary are fine: the fan of a boundary vertex is open.
bool move_keeps_orientation(const TriangleMesh& m, const Adjacency& vertex_tris, uint32_t v, const float to[3]);

// Whether any edge of the triangles around v is folded (see count_foldovers;
// a boundary edge has one triangle and is never folded).
bool folded_around(const TriangleMesh& m, const Adjacency& vertex_tris, uint32_t v, double max_angle_degrees = 150);

// Edges whose two triangles fold back onto each other: the angle between
// their normals is over `max_angle_degrees` (a fold-over).  Oriented
// manifold input, closed or with boundary; boundary edges (one triangle)
// are never folded.
size_t count_foldovers(const TriangleMesh& m, double max_angle_degrees = 150);

// Vertices on the edges count_foldovers() would count.
std::vector<uint32_t> foldover_vertices(const TriangleMesh& m, double max_angle_degrees = 150);

// Smooths folds away: vertices on folded edges and their neighbours go to
// the mean of their neighbours (boundary vertices: of their two boundary
// neighbours, see rim_neighbours), up to `rounds` times.  Returns the number
// of folded edges met.
// `coarse`: a mesh whose edges are about as long as its parts are thick (a
// control mesh).  There a neighbours' mean lies well off the surface, so
// only the folded edges' own vertices move, and a round that leaves more
// folded edges than it met is undone and ends the smoothing.  (With the
// rings moved every round, the triple torus's 290-face control mesh went
// from 3 folded edges to 7 in eight rounds and a vertex moved 1.3, four
// times its tubes' radius: its level 1 lay 3.1e-2 of the diagonal from the
// points.)
size_t untangle_folds(TriangleMesh& m, int rounds = 8, bool coarse = false);
// The same with the mesh's vertex_adjacency and rim_neighbours given (a
// caller that moved vertices only has them: shrink-wrap).
size_t untangle_folds(TriangleMesh& m, const Adjacency& adj, const std::vector<std::array<uint32_t, 2>>& rim, int rounds = 8,
                      bool coarse = false);

}  // namespace dbss
