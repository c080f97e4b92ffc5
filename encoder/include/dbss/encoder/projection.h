// Final stage of the control mesh: vertices onto the points (paper 3.1; no
// surface fitting, the butterfly scheme interpolates its control vertices).
#pragma once

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/point_index.h"

namespace dbss {

// Moves every vertex, in vertex order, to the closest of its 16 nearest
// points that turns no triangle over and folds no edge (on thin parts the very closest can lie
// on the far side); returns how many vertices found none and stayed.
size_t project_to_points(TriangleMesh& mesh, const PointIndex& points);

}  // namespace dbss
