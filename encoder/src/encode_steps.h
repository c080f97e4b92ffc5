// Steps encode_points (encode.cpp) and encode_mesh (encode_mesh.cpp) share:
// what the file's header and quantization take from the input, and the
// control mesh through Draco and back.  Internal to the encoder.
#pragma once

#include <span>

#include "dbss/encoder/encode.h"

namespace dbss {

// The header's bounding box and e.diagonal from the input's positions
// (x, y, z per vertex, at least one), then e.step and e.error from the
// options (a step given, or the error target relative to the diagonal).
void set_extent_and_step(Encoding& e, std::span<const float> xyz, const EncodeOptions& o);

// Encodes e.stages.control with Draco at e.control_bits and decodes it
// again into e.control, which is what a decoder sees and what every level
// continues from; fills the header's control-mesh fields and the chunk's
// bytes.  An error here is internal (Draco or the topology refused what
// the encoder made).  `placed` (may be null): those vertices at other
// positions, encoded instead (the point path's rounding along the surface).
Status control_mesh_through_draco(Encoding& e, const TriangleMesh* placed = nullptr);

}  // namespace dbss
