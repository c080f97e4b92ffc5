// One subdivision step: topology pass once (LevelPlan), geometry pass as
// flat loops (even copy, stencils, normals, displacements).
//
// This is the reference evaluation, shaped like spec/decoding.md: explicit
// stencil and ring tables.  The progressive decoder and the encoder's
// closed loop (LevelRefiner) run faster kernels that evaluate the same
// terms in the same order straight from the half-edge tables; tests check
// the two agree bit for bit.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "dbss/decoder/butterfly.h"
#include "dbss/decoder/normals.h"
#include "dbss/decoder/topology.h"

namespace dbss {

// Everything the geometry pass from level l to l+1 needs, built from level
// l's topology alone.
struct LevelPlan {
  uint32_t vertex_count = 0;  // V_l: odd vertex e becomes vertex V_l + e
  Stencils stencils;
  std::vector<uint32_t> rings;
  uint32_t odd_count() const noexcept { return stencils.size(); }
};

LevelPlan plan_level(const LevelTopology& t);

// positions: 3 * V_l floats.  q: one integer per odd vertex, or empty for
// plain subdivision.  Writes 3 * (V_l + E_l) floats to `out`: the evens
// unchanged, then each odd vertex at its stencil point moved by q * step
// along its unit normal.  `threads` >= 1 splits the odd vertices into
// contiguous ranges; the result is the same for any value.
void subdivide_geometry(const LevelPlan& plan, std::span<const float> positions, std::span<const int32_t> q,
                        float step, std::vector<float>& out, unsigned threads = 1);

}  // namespace dbss
