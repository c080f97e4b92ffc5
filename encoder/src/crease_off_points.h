// Untagged control vertices left off the points in a tagged control mesh
// (CreaseOptions::settle_off_points, off by default).  The builder's
// projection refuses a move that turns a triangle over; a vertex already
// outside its own ring (a tall tent of valence 3 over a small base, the
// cylinder's at seed 2: 0.036 outside the wall, past one edge of its base)
// cannot reach the points without turning one, so it stays off them.  The butterfly keeps
// control vertices at every level, so that offset is each level's
// Hausdorff distance (1.03% of the diagonal, bench/crease_bench.md,
// sixteenth session).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/point_index.h"
#include "dbss/format/container.h"

namespace dbss {

// Moves each interior vertex with no crease edge and no corner tag that
// is over a quarter of its mean edge length both from its nearest point
// and from the plane of its 8 nearest points (where they are a plane: not
// beside a line or a corner) onto that plane: to its own foot, else to
// the first of 4 steps from there toward its ring's centroid (dropped onto
// the plane of the points nearest it) where every triangle of its fan
// faces the way its ring does (the ring's vector area) with quality
// >= 0.05.  `t` is `mesh`'s topology, `tags` in its order, `count` the
// crease edges at each vertex.  Returns the number of vertices moved.
size_t settle_off_points(TriangleMesh& mesh, const LevelTopology& t, const format::Creases& tags,
                         const std::vector<uint32_t>& count, const PointIndex& points);

}  // namespace dbss
