// Who touches whom in a triangle mesh: vertex neighbours, the triangles
// around each vertex, the rim of an open mesh, and vertex normals.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"

namespace dbss {

// Vertex neighbours as CSR arrays (each neighbour once).
struct Adjacency {
  std::vector<uint32_t> offset;  // vertex_count + 1
  std::vector<uint32_t> index;
};
Adjacency vertex_adjacency(const TriangleMesh& m);

// Triangles around each vertex as CSR arrays.
Adjacency vertex_triangles(const TriangleMesh& m);

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

}  // namespace dbss
