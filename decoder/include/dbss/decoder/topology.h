// Connectivity of one subdivision level, as flat tables.
//
// Half-edge h = 3f + k runs from corner k of triangle f to corner k+1 (mod 3).
// Everything here depends only on the triangle list, never on positions, so
// it is built once per level and the geometry passes walk it as arrays.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/format/status.h"

namespace dbss {

inline constexpr uint32_t kNoHalfEdge = 0xFFFFFFFFu;

struct LevelTopology {
  uint32_t vertex_count = 0;
  std::vector<uint32_t> triangles;  // 3 per triangle, counter-clockwise
  // Opposite half-edge, or kNoHalfEdge on the boundary.
  std::vector<uint32_t> twin;
  // Edge of each half-edge.  Edges are numbered in the order of their first
  // half-edge (the one with the smaller index): the spec's canonical order.
  std::vector<uint32_t> edge_of;
  // The first half-edge of each edge.
  std::vector<uint32_t> edge_half;
  // Per vertex: an outgoing half-edge from which a counter-clockwise walk
  // (h -> twin[prev(h)]) visits its whole fan (on the boundary, the outgoing
  // boundary half-edge), the number of neighbours, and its kind: bits
  // kVertexBoundary, kVertexSharp and kVertexCreaseEnd below (0: a smooth
  // interior vertex).
  std::vector<uint32_t> vertex_start;
  std::vector<uint16_t> vertex_valence;
  std::vector<uint8_t> vertex_boundary;
  // Per edge, 1 on a crease (spec/decoding.md section 5.4); empty when the
  // level has no crease, which is how every 1.0 file decodes.
  std::vector<uint8_t> edge_crease;

  uint32_t triangle_count() const noexcept { return static_cast<uint32_t>(triangles.size() / 3); }
  uint32_t edge_count() const noexcept { return static_cast<uint32_t>(edge_half.size()); }
};

// Bits of LevelTopology::vertex_boundary.  A vertex that is not 0 never
// takes the regular 8-point fast path nor the extraordinary rule: a crease
// is a boundary inside the mesh, so the test of the hot loop stays one byte.
inline constexpr uint8_t kVertexBoundary = 1;   // on the mesh's boundary
inline constexpr uint8_t kVertexSharp = 2;      // on a crease edge, or tagged corner
inline constexpr uint8_t kVertexCreaseEnd = 4;  // a crease polyline stops here (spec 5.4)

inline uint32_t next_half(uint32_t h) noexcept { return h % 3 == 2 ? h - 2 : h + 1; }
inline uint32_t prev_half(uint32_t h) noexcept { return h % 3 == 0 ? h + 2 : h - 1; }

// Largest vertex valence the decoder accepts; higher valences are rejected as
// bad_mesh (the encoder never produces them; the stencils' cost grows with it).
inline constexpr uint32_t kMaxValence = 64;

// Topology of a control mesh.  Rejects (bad_mesh, naming the vertex or edge)
// out-of-range indices, degenerate triangles, edges with more than two
// triangles or inconsistent orientation, vertices whose triangles form more
// than one fan, unused vertices and valences over kMaxValence.
Result<LevelTopology> build_topology(uint32_t vertex_count, std::span<const uint32_t> triangles);

// Marks the control mesh's crease edges (edge[e] != 0, canonical edge
// order, edge.size() == edge_count()) and corner vertices (corner[v] != 0,
// corner.size() == vertex_count): sets edge_crease and the sharp and
// crease-end bits (spec/decoding.md section 5.4).  bad_mesh, naming it, if
// a crease edge lies on the boundary or a size is wrong.  Both empty: nothing.
Status set_creases(LevelTopology& t, std::span<const uint8_t> edge, std::span<const uint8_t> corner);

// Topology of the next level from the regular 1-to-4 split: odd vertex of
// edge e is vertex parent.vertex_count + e; triangle f becomes
//   4f+k = (v_k, m_k, m_{k+2})  for k = 0, 1, 2, and 4f+3 = (m_0, m_1, m_2),
// where v_k are f's corners and m_k the odd vertex of half-edge 3f+k.  Twins
// and vertex tables follow from the parent's without any search.
LevelTopology refine_topology(const LevelTopology& parent);

// Only the triangles of the next level (what the finest level needs).
void refine_triangles(const LevelTopology& parent, std::vector<uint32_t>& child_triangles);

}  // namespace dbss
