// Internal: a level's connectivity as raw arrays, so the same kernels serve
// the public LevelTopology (std::vector) and the progressive decoder's
// reusable, never-zeroed buffers.
#pragma once

#include <cstdint>

#include "dbss/decoder/topology.h"

namespace dbss::detail {

struct TopologyRef {
  uint32_t vertex_count = 0, face_count = 0, edge_count = 0;
  const uint32_t* tri = nullptr;           // 3 per face
  const uint32_t* twin = nullptr;          // 3 per face
  const uint32_t* edge_of = nullptr;       // 3 per face
  const uint32_t* edge_half = nullptr;     // per edge: its first half-edge
  const uint32_t* vertex_start = nullptr;  // per vertex
  const uint16_t* valence = nullptr;       // per vertex
  const uint8_t* boundary = nullptr;       // per vertex
  // Optional, 3 per face: the vertex across half-edge x, T[prev(twin(x))]
  // (kNoHalfEdge on the boundary).  Saves the stencils a dependent load per
  // wing; null means "look it up through twin".
  const uint32_t* across = nullptr;
  // Per edge, non-zero on a crease; null when the level has none.
  const uint8_t* crease = nullptr;
};

inline uint32_t across_of(const TopologyRef& t, uint32_t x) noexcept {
  if (t.across) return t.across[x];
  const uint32_t o = t.twin[x];
  return o == kNoHalfEdge ? kNoHalfEdge : t.tri[prev_half(o)];
}

inline TopologyRef ref_of(const LevelTopology& t) {
  TopologyRef r;
  r.vertex_count = t.vertex_count, r.face_count = t.triangle_count(), r.edge_count = t.edge_count();
  r.tri = t.triangles.data(), r.twin = t.twin.data(), r.edge_of = t.edge_of.data(), r.edge_half = t.edge_half.data();
  r.vertex_start = t.vertex_start.data(), r.valence = t.vertex_valence.data(), r.boundary = t.vertex_boundary.data();
  r.crease = t.edge_crease.empty() ? nullptr : t.edge_crease.data();
  return r;
}

// Half-edge h opens an edge (is its first half-edge) when it has no twin or
// its twin comes later; kNoHalfEdge is larger than any half-edge.
inline bool opens_edge(const uint32_t* twin, uint32_t h) noexcept { return twin[h] > h; }

// Number of edges opened by half-edges before 3f: where the edges of faces
// f, f+1, ... start in edge order.  Lets a thread start mid-mesh.
inline uint32_t first_edge_of_face(const TopologyRef& t, uint32_t f) noexcept {
  for (uint32_t h = 3 * f; h < 3 * t.face_count; ++h)
    if (opens_edge(t.twin, h)) return t.edge_of[h];
  return t.edge_count;
}

// Where the refinement of a parent level writes the child level's tables.
// tri, edge_half and across may be null: not wanted.
struct TopologyOut {
  uint32_t* tri;
  uint32_t* twin;
  uint32_t* edge_of;
  uint32_t* edge_half;
  uint32_t* vertex_start;
  uint16_t* valence;
  uint8_t* boundary;
  uint32_t* across = nullptr;
  uint8_t* crease = nullptr;  // written only when the parent has creases
};

// The child tables of parent faces [fb, fe) (their 4 children each, and the
// odd vertices of the edges they open), and of parent vertices [vb, ve).
// Each entry is written by exactly one call for disjoint ranges.
void refine_faces(const TopologyRef& parent, uint32_t fb, uint32_t fe, const TopologyOut& child);
void refine_vertices(const TopologyRef& parent, uint32_t vb, uint32_t ve, const TopologyOut& child);
// Only the child triangles of parent faces [fb, fe).
void refine_triangle_range(const TopologyRef& parent, uint32_t fb, uint32_t fe, uint32_t* child_tri);

}  // namespace dbss::detail
