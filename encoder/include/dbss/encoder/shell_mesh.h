// The carved solid's outer faces as a closed triangle mesh (paper, 3.1).
#pragma once

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/cell_carving.h"
#include "dbss/encoder/mesh_info.h"
#include "dbss/format/status.h"

namespace dbss {

// Every face between a solid cell and an air cell becomes a quad with its
// normal towards the air, split into two triangles; vertices are grid
// corners.  The paper's collapse types then simplify cells with many air
// faces: five air faces (Type 1) collapse the four air corners into one;
// four air faces not forming a ribbon (Type 2) collapse the two air corners;
// three air faces around one corner (Type 3) cut that corner off; every
// other cell (Type 4, the general case) keeps its air quads, each split into
// two triangles.  Collapses only merge corners that no other solid cell
// uses.  Because carve() leaves a well-composed solid, the result is a
// closed, oriented 2-manifold whose Euler characteristic is twice the
// solid's; both are checked, and a failed check is an internal error.
// `info`, when given, receives the shell's mesh_info (computed for the
// checks here anyway; the 80k-triangle shell of a 35k-point scan took 2% of
// the control mesh's time to describe a second time).
Result<TriangleMesh> triangulate_shell(const CellGrid& grid, bool collapse_types = true, MeshInfo* info = nullptr);

}  // namespace dbss
