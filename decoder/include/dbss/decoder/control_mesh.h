// Decoding the CTRL chunk's Draco bytes into the level-0 mesh.
#pragma once

#include <cstdint>
#include <span>

#include "dbss/decoder/mesh.h"
#include "dbss/format/status.h"

namespace dbss {

// Decodes a Draco-compressed triangle mesh.  Points Draco duplicated for the
// same position value are merged by attribute value index, so the result is
// indexed; vertices are numbered in Draco's value order and triangles keep
// Draco's face order, which the encoder also continues from (the stream never
// depends on the encoder's own vertex order).  Safe on untrusted bytes: at
// most `max_vertices` vertices and `max_triangles` triangles are accepted;
// failures come back as ErrorCode::compression or bad_mesh.
Result<TriangleMesh> decode_control_mesh(std::span<const uint8_t> draco_bytes, uint64_t max_vertices,
                                         uint64_t max_triangles);

}  // namespace dbss
