// QEM simplification of the shrink-wrapped mesh to the control mesh size.
#pragma once

#include <cstdint>

#include "dbss/decoder/mesh.h"
#include "dbss/format/status.h"

namespace dbss {

struct SimplifyStats {
  uint32_t faces_before = 0, faces_after = 0;
};

// Garland-Heckbert quadric edge collapses down to `target_faces` triangles,
// through OpenMesh's decimater: its collapse test keeps the link condition
// (so the mesh stays manifold and keeps its genus), its normal-flipping
// module rejects collapses that turn a triangle over (more than 60 degrees),
// and its aspect-ratio module rejects needles.  A closed mesh loses two
// triangles per collapse, so an even target is met exactly unless every
// remaining collapse is refused; then fewer collapses happen (see stats).
Result<TriangleMesh> simplify_mesh(const TriangleMesh& mesh, uint32_t target_faces, SimplifyStats* stats = nullptr);

// The default control mesh size for a shell: an eighth of its triangles,
// at least 96 + 64 * genus (enough room around every handle) and at most
// 4000, rounded to even.
uint32_t default_control_faces(uint32_t shell_faces, int64_t genus);

}  // namespace dbss
