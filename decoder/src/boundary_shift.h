// Internal: spec/decoding.md section 7a (format 1.3), the second move of
// boundary odd vertices, across the boundary within the surface.  One pass
// over a level's boundary edges after the normal displacement (section 7),
// so the odd-vertex kernels stay as they are.
#pragma once

#include <cstdint>

#include "dbss/decoder/odd_chooser.h"
#include "topology_ref.h"

namespace dbss::detail {

// For every boundary edge of `t` (the level being refined; p its
// positions), the k-th in edge order: moves odd vertex e (out_odd[3e..],
// as section 7 left it) by bq[k] * step along b = t x n / |t x n|, with n
// the odd vertex's normal from the undisplaced child level (evens p, odds
// per half-edge in per_half, as the stencil pass wrote them).  With
// `choose`, bq[k] is chosen by it (and written to chosen[k]) instead.
void shift_boundary(const TopologyRef& t, const float* p, const float* per_half, const int32_t* bq,
                    const BoundaryChooser* choose, int32_t* chosen, float step, float* out_odd);

}  // namespace dbss::detail
