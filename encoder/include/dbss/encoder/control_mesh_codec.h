// Compressing the control mesh for the CTRL chunk.
#pragma once

#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/format/status.h"

namespace dbss {

// Draco's encoder speeds the encoder tries for the CTRL chunk, keeping the
// smaller: 0 predicts positions with the constrained multi-parallelogram,
// 2 with the plain parallelogram (both keep Draco's own choice of
// edgebreaker method, valence on the larger meshes).  On control meshes
// this coarse (140-1,600 vertices, 11 bits) the plain parallelogram is
// smaller: 0.6-5.4% fewer CTRL bytes on six libcgal-demo meshes' control
// meshes (bunny00 -0.6%, armadillo -1.7%, shark -1.6%, camel -2.6%,
// elephant -4.8%, cow -5.4%), 2-8% on three point clouds'; but on
// armadillo's at 9-10 bits speed 0 was ~50 bytes smaller (bench/lod_bench.md,
// fifteenth session, bench/ctrl_codec_probe).  Any speed writes a Draco 1.5
// bitstream the decoder reads unchanged (format section 8); speed 10 would
// store floats.  Encoding the control mesh twice costs milliseconds.
inline constexpr int kControlDracoSpeeds[] = {2, 0};

struct ControlCodecOptions {
  int position_bits = 16;  // Draco position quantization, 1..30; 0 = lossless float
  int speed = 2;           // Draco encoder speed 0 .. 10 (fastest); 0 and 2 are the smallest (see above)
};

// Draco position bits that round the control vertices to about half the
// displacement step: ceil(log2(largest extent of the mesh / step)), within
// 8..16 (16 was the fixed choice before; more is never needed at the
// steps the encoder makes).
int control_bits_for_step(const TriangleMesh& mesh, float step);

// Draco's grid spacing (the mesh's largest extent over 2^bits) allowed per
// unit of the level-0 surface's distance to the points.
inline constexpr double kControlGridPerError = 1.5;

// Draco position bits for the point path: the fewest whose grid spacing is
// at most kControlGridPerError times `level0_distance` (model units, the
// control mesh's own distance to the points), and never more than
// control_bits_for_step's.  A control vertex is an even vertex of every
// level and never moves again, but at level L it is one vertex in 4^L: its
// rounding shows in level 0's error, and the odd vertices around it are
// sampled from the points after it is rounded (closed loop) and take the
// rounding up.  So level 0's own error, not the step, sets what rounding
// is harmless (issue 15's sweep on five sampled shapes, 30k points: 10
// bits instead of the step's 12-13 cost 21-23% fewer level-0 bytes for
// 1-2.5% more level-0 error and no change at the finer levels beyond the
// chaos of a different rounding).  The encoder then places each vertex on
// the grid point nearest its surface (control_rounding.h), which leaves
// about a quarter of plain rounding's offset along the normal.  (Reverted
// once because level_error_test's sparse torus rose 2.8% from level 4 to 5;
// over seeds 1-7 that rise passes 2% on 3 of 14 tori at the step's bits
// too: it is the plain butterfly past the points, not these bits.)
// Within 8..16; a non-positive or non-finite distance falls back to the
// step's bits.
int control_bits_for_error(const TriangleMesh& mesh, double level0_distance, float step);

// Draco bytes for `mesh`.  Draco quantizes positions and reorders vertices,
// so callers continue from decode_control_mesh() of these bytes, never from
// `mesh` itself.
Result<std::vector<uint8_t>> encode_control_mesh(const TriangleMesh& mesh, const ControlCodecOptions& options = {});

}  // namespace dbss
