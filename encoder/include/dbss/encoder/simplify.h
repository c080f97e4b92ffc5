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
// valence under 3, turns a triangle by more than 60 degrees, or makes a
// needle (SimplifyOptions::needle).  A closed mesh loses two triangles per
// collapse, so an even target is met exactly unless every remaining
// collapse is refused.
//
// `mesh` may have a boundary (an oriented manifold whose boundary edges are
// in one triangle).  The boundary is kept in shape: its edges add weighted
// planes (through the edge, perpendicular to its triangle) to its
// vertices' quadrics, an edge from the boundary inwards collapses onto its
// boundary end, and an inner edge joining two boundary vertices never
// collapses.  A boundary edge's collapse removes one triangle, so the result
// may have one triangle less than `target_faces`.
struct SimplifyOptions {
  // A moved triangle whose doubled area is under `needle` times its longest
  // side squared is a needle and its collapse is refused: 0.05 is a
  // smallest angle of about 2.9 degrees, 0.01 about 0.6.  The point path
  // keeps 0.05 (its shape stage and valence limits were tuned on it).  A
  // mesh input more than 32 times finer than its control mesh takes 0.01
  // (mesh_control_needle): a refused collapse leaves the heap for good,
  // and on fine inputs the refusals piled up near the end, where the cheap
  // thin collapses in smooth parts were refused and QEM ate the features
  // instead (issue 18).  The armadillo subdivided to 998k triangles, to
  // 4000 faces: in the last tenth of the run (103k to 4k faces) 0.05
  // refused 6016 collapses as needles, 7973 as turns and 1299 for the
  // link, and the heap ran dry at 5454 faces with a mean error of 7.6e-3
  // of the diagonal; 0.01 refused 99, 834 and 188 and reached 4000 faces
  // at 8.9e-4.
  double needle = 0.05;
};

Result<TriangleMesh> simplify_mesh(const TriangleMesh& mesh, uint32_t target_faces, SimplifyStats* stats = nullptr,
                                   const SimplifyOptions& options = {});

// The default control mesh size for a shell: a 24th of its triangles,
// at least 96 + 64 * genus (enough room around every handle) and at most
// 4000, rounded to even.
uint32_t default_control_faces(uint32_t shell_faces, int64_t genus);

}  // namespace dbss
