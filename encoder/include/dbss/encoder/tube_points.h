// Points for the band a scan missed right round a tube.  Where the points
// end at two rims that look like a cut tube's two ends (point_rims.h) and a
// closed surface built from them caps the ends instead of joining them (a
// lost handle), the gap is sampled along the tube a bridge would follow:
// rings round the Hermite curve that leaves one rim against its axis and
// enters the other along its own, their radius blended from one rim's tube
// radius (PointRim::tube_radius) to the other's, as densely as the scan.
// Carved with these points, the gap is no gap: the surface keeps the handle
// the way it does on a complete scan, without a stage of its own after the
// carving.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "dbss/encoder/point_index.h"
#include "dbss/encoder/point_rims.h"

namespace dbss {

struct TubePoints {
  PointCloud points;     // the input's points, then the added ones
  size_t added = 0;      // points added (points.size() - the input's)
  size_t tubes = 0;      // gaps sampled
  double area = 0;       // the area the added points cover (added x spacing^2), model units^2: no point of the scan supports it
};

// Samples the gap of each pair (indices into `rims`) at `spacing` (the side
// of the area each of the scan's points stands for); the
// added points keep at least 0.75 spacing from the scan's own (where a cut
// is oblique the scan runs on into the tube's path on one side).
TubePoints sample_cut_tubes(const PointIndex& index, const std::vector<PointRim>& rims,
                            const std::vector<std::pair<size_t, size_t>>& pairs, double spacing);

}  // namespace dbss
