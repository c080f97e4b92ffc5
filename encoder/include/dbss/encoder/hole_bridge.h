// Bridging two holes that face each other across a gap: where a scan
// missed a band all the way round a tube (a handle, a leg, a ring of a
// double torus), the sheet has two boundary loops, one at each cut end.
// Closing each with its own disk cuts the handle and loses a genus; the
// right closure is a tube joining the two loops.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"

namespace dbss {

// Loops (as boundary_loops gives them: vertices in the order of the
// boundary half-edges, the surface on the left) that face each other are
// paired and each pair joined by a tube: rings about two `edge`s apart,
// placed on a cubic Hermite curve that leaves one loop and enters the other
// along the loops' axes, zipped to each other and to the loops.  Two loops
// face each other when each one's plane faces the other across the gap (as
// the two ends of a cut tube do; not as two holes on the two sides of a
// plate do), the surface round each runs along its axis as a tube's wall
// does (not across it, as round a hole in a wall), their sizes are within
// a factor of two, and the gap is under five times the larger loop's
// radius.  A tube that crosses the mesh all
// the way round (through a part in its way) is not built.  Bridged loops
// are removed from `loops`; the new vertices are appended to `added`.
// Returns the number of tubes built.  `unbridged_pairs`, when given, gets
// the number of disjoint pairs left that half fit the rule (one loop faces
// the other, the walls lean along the axes): capping them may cut a handle.
// `m` must be an oriented manifold with boundary; it stays one.
size_t bridge_facing_loops(TriangleMesh& m, std::vector<std::vector<uint32_t>>& loops, double edge,
                           std::vector<uint32_t>& added, size_t* unbridged_pairs = nullptr);

}  // namespace dbss
