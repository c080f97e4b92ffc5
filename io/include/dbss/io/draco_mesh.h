// Draco bytes of a triangle mesh (positions and triangles only): the one
// place dbss builds a draco::Mesh, for the control mesh's CTRL chunk
// (encoder/control_mesh_codec) and for glTF levels under
// KHR_draco_mesh_compression (io/gltf_draco).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/format/status.h"

namespace dbss::io {

struct DracoEncodeOptions {
  int position_bits = 0;  // Draco position quantization, 1..30; 0 = lossless float
  int speed = -1;         // Draco encoder speed 0 (smallest) .. 10 (fastest); -1 = Draco's default
};

// `what` names the mesh in messages ("control mesh", "glTF level").  A
// triangle naming a missing vertex is invalid_argument; Draco's own failure
// is internal.
Result<std::vector<uint8_t>> draco_encode(const TriangleMesh& mesh, const DracoEncodeOptions& options,
                                          const std::string& what);

}  // namespace dbss::io
