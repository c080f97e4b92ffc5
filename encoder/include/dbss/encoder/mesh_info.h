// Manifoldness, components, boundary loops and genus of a triangle mesh.
#pragma once

#include <cstdint>

#include "dbss/decoder/mesh.h"
#include "dbss/format/status.h"

namespace dbss {

// Topological facts about a mesh, from the decoder's own topology builder.
struct MeshInfo {
  bool manifold = false;  // oriented 2-manifold, every edge in 1 or 2 triangles
  bool closed = false;    // no boundary edge
  uint32_t components = 0;
  uint32_t boundary_loops = 0;  // closed walks of boundary edges; 0 when closed
  int64_t euler = 0;      // V - E + F
  // Sum over components of (2 - euler - boundary loops) / 2: the handles,
  // for open components too (a disc or a tube has genus 0).
  int64_t genus = 0;
  Status status;          // why it is not manifold
};
MeshInfo mesh_info(const TriangleMesh& mesh);

// The same counts for a mesh already known to be an oriented manifold
// (prepare_mesh_input checked it), without the decoder's topology limits:
// an input mesh may have vertices of any valence (a UV sphere's poles),
// which only the control mesh must not.
MeshInfo mesh_counts(const TriangleMesh& mesh);

}  // namespace dbss
