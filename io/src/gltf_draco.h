// Draco compression of one level for glTF's KHR_draco_mesh_compression.
#pragma once

#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/format/status.h"

namespace dbss::io_detail {

// A level as Draco bytes, with what the glTF accessors must declare about
// the mesh a Draco decoder gets back from them: its point and face counts,
// the POSITION attribute's id, and the decoded positions' bounds (the
// quantized values, not the originals).
struct DracoLevel {
  std::vector<uint8_t> bytes;
  size_t points = 0, faces = 0;
  int position_id = 0;
  double min[3] = {0, 0, 0}, max[3] = {0, 0, 0};
};

// `bits` position quantization bits (1..30), edgebreaker at Draco's default
// speed.  internal when Draco refuses or cannot decode its own output.
Result<DracoLevel> draco_level(const TriangleMesh& mesh, int bits);

}  // namespace dbss::io_detail
