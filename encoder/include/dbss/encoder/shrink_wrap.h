// Shrink-wrapping (paper 3.1, after Jeong and Kim): alternate projection of
// every vertex towards its closest point and tangential smoothing, until the
// mesh stops moving.
#pragma once

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/point_index.h"

namespace dbss {

struct ShrinkWrapOptions {
  int max_iterations = 40;
  double step = 0.5;       // fraction of the way to the closest point per iteration, (0, 1]
  double smoothing = 0.5;  // tangential relaxation weight per iteration, [0, 1)
  int rounding_iterations = 5;  // first iterations use full (not only tangential) smoothing
  // Stop when the mean vertex move of an iteration is under this fraction of
  // the mean edge length.
  double tolerance = 1e-3;
};

struct ShrinkWrapStats {
  int iterations = 0;
  double mean_distance = 0;  // mean vertex-to-closest-point distance at the end
  double max_distance = 0;
  size_t untangled = 0;  // folded edges smoothed out after the last iteration
  size_t undone = 0;     // vertex moves undone because they made triangles cross
};

// Moves mesh vertices in place; connectivity is unchanged.
ShrinkWrapStats shrink_wrap(TriangleMesh& mesh, const PointIndex& points, const ShrinkWrapOptions& options = {});

}  // namespace dbss
