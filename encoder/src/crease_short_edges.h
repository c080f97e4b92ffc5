// Short edges under long rings in a tagged control mesh
// (CreaseOptions::short_collapses).  QEM and the alignment leave pairs of
// untagged vertices a hundredth of the part apart beside the feature
// lines, each with a ring reaching 10-45 of that edge's lengths across the
// faces; the butterfly's stencil puts the short edge's level-1 odd vertex
// 1.5-3 edge lengths off its midpoint, past the line or off the face,
// where the displacement does not bring it back (the anchor's level-3
// Hausdorff distance at 40,000 points, seeds 1-3, bench/crease_bench.md
// fifteenth session).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/decoder/topology.h"
#include "dbss/format/container.h"

namespace dbss {

// Collapses each untagged interior edge u-v shorter than a kShort share of
// the longest edge at u or v into one of its ends (never a vertex with a
// crease edge or a corner tag into another: such a vertex is the one
// kept), where the collapse keeps the mesh manifold (u and v share only
// the edge's two far corners), every remaining triangle of the removed
// end turned less than 30 degrees and not a sliver, and the kept vertex's
// valence at most 10 or the larger of the two.  The kept vertex stays
// where it is, on the points.  `t` is `mesh`'s topology, `tags` in its
// order, `count` the crease edges at each vertex.  Returns the number of
// collapses; when any, the mesh's vertices are renumbered (the removed
// ones dropped), and `tags`, `count` and `collapsed` (the new topology)
// follow.
size_t collapse_short_edges(TriangleMesh& mesh, const LevelTopology& t, format::Creases& tags, std::vector<uint32_t>& count,
                            LevelTopology& collapsed);

}  // namespace dbss
