// The shaping pass again on a tagged control mesh (CreaseOptions::
// shape_after_tags, issue 16 item 0): the alignment to the feature lines
// (crease_align.h), the snap onto the sides' planes, the sliver flips and
// the short-edge collapses all run after the control mesh's shaping stage
// (mesh_shape.h) and leave slivers and high valences of their own beside
// the lines.  Edge flips toward valence 6 and away from slivers, and moves
// of sliver vertices from point to point (ShapeOptions::snap: they stay on
// the points), with the lines held: no tagged edge is flipped, and no
// vertex with a crease edge or a corner tag moves.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/mesh_shape.h"
#include "dbss/encoder/point_index.h"
#include "dbss/format/container.h"

namespace dbss {

// Shapes `mesh` (topology `t`, `tags` in t's edge order, `count` the
// crease edges at each vertex) as improve_shape does with `points` and
// ShapeOptions::snap, under those locks.  Vertices keep their numbers, so
// the corner tags and `count` hold as they are; when an edge was flipped,
// `shaped` is the new topology and `tags.edge` is in its order.  Returns
// the pass's figures (flips, moves, the shape before and after).
ShapeStats shape_tagged_mesh(TriangleMesh& mesh, const LevelTopology& t, format::Creases& tags, const std::vector<uint32_t>& count,
                             const PointIndex& points, LevelTopology& shaped);

}  // namespace dbss
