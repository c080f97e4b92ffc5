// Internal: the geometry of one refinement step evaluated straight from the
// parent's half-edge tables, one contiguous range of parent faces per call.
// Same arithmetic, term for term, as Stencils + apply_stencils and
// odd_normals (spec/decoding.md sections 5-7), without materialising the
// stencil, ring or normal tables: each level is evaluated once, so a table
// would cost more to write than it saves.
#pragma once

#include <cstdint>

#include "dbss/decoder/kernels.h"
#include "dbss/decoder/odd_chooser.h"
#include "topology_ref.h"

namespace dbss::detail {

// Computes the stencil point of every edge opened by faces [fb, fe) of `t`
// (p: the level's positions) and writes it either to odd[3e..3e+2] (e its
// edge number), or, when `odd` is null, to per_half[3x..3x+2] for both
// half-edges x of the edge: the normal pass then finds the ring of an odd
// vertex in the two triangles of its edge, without chasing edge numbers.
//
// For the same edges, displaced_points: the normal at the odd vertex from
// the undisplaced child level (evens p, odds per half-edge as
// stencil_points wrote them), and out[3e..] = odd vertex moved by q[e] *
// step along it.  With `finite` (every float of p and per_half is finite),
// an edge whose q[e] is 0 and whose point has no -0 coordinate is copied
// without its normal: the same bits (zero_displacement.h).
//
// displaced_points_chosen: the same, with each q[e] chosen by `choose` from
// the undisplaced point and its unit normal (as this pass computes them)
// and written to q[e]: the encoder's closed loop, through the decoder's own
// arithmetic.
//
// One instruction set's build of the three, chosen once per decoder (not
// per call): every build gives the same bits.
struct OddVertexKernels {
  void (*stencil_points)(const TopologyRef& t, const float* p, uint32_t fb, uint32_t fe, float* odd, float* per_half);
  void (*displaced_points)(const TopologyRef& t, const float* p, const float* per_half, const int32_t* q, float step,
                           uint32_t fb, uint32_t fe, float* out, bool finite);
  void (*displaced_points_chosen)(const TopologyRef& t, const float* p, const float* per_half,
                                  const OddChooser& choose, int32_t* q, float step, uint32_t fb, uint32_t fe,
                                  float* out);
};

// The build `choice` asks for, among those this processor runs.
OddVertexKernels select_kernels(Kernels choice);

}  // namespace dbss::detail
