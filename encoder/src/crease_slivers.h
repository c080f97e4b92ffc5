// Slivers along a tagged line (CreaseOptions::sliver_flips): a control
// triangle whose tagged edge u-w has its third corner c on the segment
// u-w.  The line then runs through c on one side and past it on the
// other, and c, untagged, takes the extraordinary rule with a ring over
// both faces: its edges' level-1 odd vertices land beside the line
// (bench/crease_bench.md, fourteenth session: the anchor's level-3
// Hausdorff distance at seeds 1 and 2, the fandisk's at seed 3).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/decoder/topology.h"
#include "dbss/format/container.h"

namespace dbss {

// Flips each such tagged edge u-w (triangles (u, w, c) and (w, u, d)) to
// c-d, moves c onto the segment, and moves the tag onto u-c and c-w: the
// tagged polyline keeps its ends and its line, the sliver is gone, and c
// becomes an ordinary crease vertex.  A flip is made only when c has no
// crease edge, no corner tag and is not on the boundary, c-d is not an
// edge yet, and the two new triangles and c's own triangles keep their
// orientation (no fold).  `t` is `mesh`'s topology, `tags` in its edge
// order, `count` the crease edges at each vertex.  Returns the number of
// flips; when any, `mesh.triangles`, `tags.edge` (in the new topology's
// order, given in `flipped`), `count` and c's position are updated.
size_t flip_slivers(TriangleMesh& mesh, const LevelTopology& t, format::Creases& tags, std::vector<uint32_t>& count,
                    LevelTopology& flipped);

}  // namespace dbss
