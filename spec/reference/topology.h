// decoding.md section 3: half-edges, canonical edge order, valence, boundary
// and fans, plus the manifold test of section 2 step 5. Internal to dbss_ref.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace dbss_ref::detail {

inline constexpr uint32_t kNone = UINT32_MAX;

// Half-edge h = 3f + k runs from T[h] to T[next(h)].
inline uint32_t next(uint32_t h) { return h - h % 3 + (h % 3 + 1) % 3; }
inline uint32_t prev(uint32_t h) { return h - h % 3 + (h % 3 + 2) % 3; }

struct Topology {
  uint32_t vertex_count = 0;
  std::vector<uint32_t> T;          // corners; T[h] is the start of half-edge h
  std::vector<uint32_t> twin;       // kNone on the boundary
  std::vector<uint32_t> edge_of;    // edge of each half-edge
  std::vector<uint32_t> edge_half;  // first (smaller) half-edge of each edge
  std::vector<uint32_t> valence;    // triangles around the vertex, +1 on the boundary
  std::vector<uint8_t> boundary;
  std::vector<uint32_t> out_boundary;  // the vertex's outgoing half-edge without twin
  std::vector<uint32_t> in_boundary;   // the vertex's incoming half-edge without twin
  std::vector<uint32_t> triangles_at;  // triangles using the vertex (0 = unused)

  uint32_t edge_count() const { return static_cast<uint32_t>(edge_half.size()); }
};

// Builds the topology of `triangles` over `vertex_count` vertices. Returns an
// empty string if the mesh is an oriented 2-manifold as decoding.md section
// 2 step 5 defines it (valence limit aside, which the caller checks), else
// says what is wrong. Unused vertices are allowed here.
std::string build_topology(uint32_t vertex_count, const std::vector<uint32_t>& triangles,
                           Topology& out);

// decoding.md section 5.3: s_j(k) for 3 <= k <= 64, 0 <= j < k.
double butterfly_weight(uint32_t k, uint32_t j);

}  // namespace dbss_ref::detail
