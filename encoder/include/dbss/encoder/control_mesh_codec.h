// Compressing the control mesh for the CTRL chunk.
#pragma once

#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/format/status.h"

namespace dbss {

struct ControlCodecOptions {
  int position_bits = 16;  // Draco position quantization, 1..30; 0 = lossless float
  int speed = 0;           // Draco encoder speed 0 (smallest) .. 10 (fastest)
};

// Draco position bits that round the control vertices to about half the
// displacement step: ceil(log2(largest extent of the mesh / step)), within
// 8..16 (16 was the fixed choice before; more is never needed at the
// steps the encoder makes).
int control_bits_for_step(const TriangleMesh& mesh, float step);

// Draco bytes for `mesh`.  Draco quantizes positions and reorders vertices,
// so callers continue from decode_control_mesh() of these bytes, never from
// `mesh` itself.
Result<std::vector<uint8_t>> encode_control_mesh(const TriangleMesh& mesh, const ControlCodecOptions& options = {});

}  // namespace dbss
