// Loop subdivision (Loop 1987), for the full-vertex DSS baseline that `dbss
// compare` measures dbss against.  It is an approximating scheme: every
// vertex moves at every level, which is why a DSS must store a displacement
// per vertex per level.  Not part of the format; the decoder never uses it.
#pragma once

#include <span>
#include <vector>

#include "dbss/decoder/topology.h"

namespace dbss {

// Loop's even-vertex weight for interior valence k >= 3:
// beta = (5/8 - (3/8 + cos(2 pi / k) / 4)^2) / k.
double loop_beta(uint32_t k) noexcept;

// One Loop step on `t`'s connectivity (the same 1-to-4 split and vertex
// numbering as the butterfly levels: refine_topology(t) holds the child
// triangles).  positions: 3 * V floats; writes 3 * (V + E) to `out`.
// Interior rules: even (1 - k beta) v + beta sum(neighbours), odd
// 3/8 (a + b) + 1/8 (c + d); boundary: even 3/4 v + 1/8 (b0 + b1), odd
// 1/2 (a + b).
void loop_subdivide(const LevelTopology& t, std::span<const float> positions, std::vector<float>& out);

}  // namespace dbss
