// Small geometric helpers the reconstruction stages share.
#pragma once

#include <array>
#include <utility>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/point_index.h"

namespace dbss {

// Vertex neighbours as CSR arrays (each neighbour once).
struct Adjacency {
  std::vector<uint32_t> offset;  // vertex_count + 1
  std::vector<uint32_t> index;
};
Adjacency vertex_adjacency(const TriangleMesh& m);

// Triangles around each vertex as CSR arrays.
Adjacency vertex_triangles(const TriangleMesh& m);

// Whether moving vertex v to `to` keeps every triangle around it facing
// within 90 degrees of where it faced before (no triangle turns over).
// Meshes with boundary are fine: the fan of a boundary vertex is open.
bool move_keeps_orientation(const TriangleMesh& m, const Adjacency& vertex_tris, uint32_t v, const float to[3]);

// Whether any edge of the triangles around v is folded (see count_foldovers;
// a boundary edge has one triangle and is never folded).
bool folded_around(const TriangleMesh& m, const Adjacency& vertex_tris, uint32_t v, double max_angle_degrees = 150);

// The neighbours of each vertex along the boundary (edges in one triangle)
// of an oriented manifold: {previous, next} in the direction of the boundary
// half-edges.  Interior vertices get {kNotOnRim, kNotOnRim}; a vertex where
// the surface pinches (several boundary edges in or out) gets {v, v}, so
// smoothing along the rim leaves it where it is.  Smoothing a boundary
// vertex towards its rim neighbours rather than all its neighbours keeps an
// open sheet from shrinking away from its edge.
inline constexpr uint32_t kNotOnRim = 0xFFFFFFFFu;
std::vector<std::array<uint32_t, 2>> rim_neighbours(const TriangleMesh& m);

// Area-weighted unit vertex normals (zero for isolated or degenerate fans;
// a boundary vertex's from its open fan).
std::vector<std::array<double, 3>> vertex_normals(const TriangleMesh& m);

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
size_t untangle_folds(TriangleMesh& m, int rounds = 8);

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
};
PointPlane fit_plane(const PointCloud& points, const uint32_t* indices, size_t count);

// Mean and largest distance from each vertex to the surface of the points,
// taken as the least-squares plane of its 8 nearest points.
SurfaceDistance vertices_to_points_surface(const std::vector<float>& vertices_xyz, const PointIndex& points);

// Pairs (f < g) of triangles that share no vertex yet intersect, sorted; a
// uniform grid of triangle bounds narrows the candidates.
std::vector<std::pair<uint32_t, uint32_t>> self_intersections(const TriangleMesh& m);
size_t count_self_intersections(const TriangleMesh& m);

// Where triangles cross, puts their vertices back at their positions in
// `safe` (the same mesh before some moves, without crossings), up to
// `rounds` times, then every vertex.  Returns how many vertex moves were
// undone.
size_t undo_self_intersections(TriangleMesh& m, const std::vector<float>& safe, int rounds = 8);

// Where triangles cross and no earlier state is at hand (after edge
// collapses), moves their vertices to their neighbours' mean (boundary
// vertices: their two boundary neighbours' mean), up to `rounds` times.
// Returns the number of vertex moves.
size_t relax_self_intersections(TriangleMesh& m, int rounds = 10);

// Winding-number inside test of a closed, outward-oriented mesh.
bool inside_mesh(const TriangleMesh& m, const std::array<double, 3>& p);

}  // namespace dbss
