#include "dbss/decoder/control_mesh.h"

#include <draco/compression/decode.h>

#include <cmath>
#include <limits>
#include <string>

namespace dbss {

Result<TriangleMesh> decode_control_mesh(std::span<const uint8_t> bytes, uint64_t max_vertices,
                                         uint64_t max_triangles) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok() || type.value() != draco::TRIANGULAR_MESH)
    return Status(ErrorCode::compression, "control mesh: not a Draco triangle mesh");
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok())
    return Status(ErrorCode::compression, "control mesh: Draco: " + decoded.status().error_msg_string());
  const draco::Mesh& mesh = *decoded.value();
  const draco::PointAttribute* pos = mesh.GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (!pos || pos->num_components() != 3)
    return Status(ErrorCode::bad_mesh, "control mesh: no 3-component position attribute");
  const uint64_t values = pos->size();
  if (values > max_vertices || mesh.num_faces() > max_triangles)
    return Status(ErrorCode::limit_exceeded, "control mesh: " + std::to_string(values) + " vertices and " +
                                                 std::to_string(mesh.num_faces()) + " triangles, over the limits");

  TriangleMesh out;
  out.positions.resize(values * 3);
  for (uint32_t v = 0; v < values; ++v) {
    if (!pos->ConvertValue<float, 3>(draco::AttributeValueIndex(v), &out.positions[3 * size_t{v}]))
      return Status(ErrorCode::bad_mesh, "control mesh: position " + std::to_string(v) + " cannot be read as float");
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(out.positions[3 * size_t{v} + k]))
        return Status(ErrorCode::bad_mesh, "control mesh: position " + std::to_string(v) + " is not finite");
  }
  out.triangles.resize(size_t{mesh.num_faces()} * 3);
  for (uint32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto& face = mesh.face(draco::FaceIndex(f));
    for (int k = 0; k < 3; ++k) {
      if (face[k].value() >= mesh.num_points())
        return Status(ErrorCode::bad_mesh, "control mesh: triangle " + std::to_string(f) + " names a missing point");
      out.triangles[3 * size_t{f} + k] = pos->mapped_index(face[k]).value();
    }
  }
  // Only used values are vertices; an unused one would be an isolated vertex.
  std::vector<uint8_t> used(values, 0);
  for (uint32_t i : out.triangles) {
    if (i >= values) return Status(ErrorCode::bad_mesh, "control mesh: a triangle names a missing vertex");
    used[i] = 1;
  }
  for (uint64_t v = 0; v < values; ++v)
    if (!used[v]) return Status(ErrorCode::bad_mesh, "control mesh: vertex " + std::to_string(v) + " is on no triangle");
  return out;
}

}  // namespace dbss
