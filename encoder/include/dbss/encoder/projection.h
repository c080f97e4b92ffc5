// Final stage of the control mesh: vertices onto the points (paper 3.1; no
// surface fitting, the butterfly scheme interpolates its control vertices).
#pragma once

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/point_index.h"

namespace dbss {

// Moves every vertex to its closest point, in vertex order, except where
// that would turn a triangle over (thin parts, where the closest point can
// lie on the far side); returns how many vertices were left in place.
size_t project_to_points(TriangleMesh& mesh, const PointIndex& points);

}  // namespace dbss
