// QEM simplification of the shrink-wrapped mesh to the control mesh size.
#pragma once

#include <cstdint>

#include "dbss/decoder/mesh.h"
#include "dbss/format/status.h"

namespace dbss {

struct SimplifyStats {
  uint32_t faces_before = 0, faces_after = 0;
};

// Garland-Heckbert quadric edge collapses (area-weighted plane quadrics,
// optimal point when well conditioned) down to `target_faces` triangles.  A
// collapse is refused if it breaks the link condition (the mesh stays a
// manifold of the same genus, components and boundary loops), leaves a
// valence under 3, turns a triangle by more than 60 degrees, or makes one
// with an angle under about 3 degrees.  A closed mesh loses two triangles
// per collapse, so an even target is met exactly unless every remaining
// collapse is refused.
//
// `mesh` may have a boundary (an oriented manifold whose boundary edges are
// in one triangle).  The boundary is kept in shape: its edges add weighted
// planes (through the edge, perpendicular to its triangle) to its
// vertices' quadrics, an edge from the boundary inwards collapses onto its
// boundary end, and an inner edge joining two boundary vertices never
// collapses.  A boundary edge's collapse removes one triangle, so the result
// may have one triangle less than `target_faces`.
Result<TriangleMesh> simplify_mesh(const TriangleMesh& mesh, uint32_t target_faces, SimplifyStats* stats = nullptr);

// The default control mesh size for a shell: a 24th of its triangles,
// at least 96 + 64 * genus (enough room around every handle) and at most
// 4000, rounded to even.
uint32_t default_control_faces(uint32_t shell_faces, int64_t genus);

}  // namespace dbss
