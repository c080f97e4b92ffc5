#include "dbss/io/draco_mesh.h"

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

namespace dbss::io {

Result<std::vector<uint8_t>> draco_encode(const TriangleMesh& in, const DracoEncodeOptions& options,
                                          const std::string& what) {
  if (in.positions.size() % 3 != 0 || in.triangles.size() % 3 != 0 || in.triangle_count() == 0)
    return Status(ErrorCode::invalid_argument, what + ": positions or triangles are not whole triples");
  if (options.position_bits < 0 || options.position_bits > 30 || options.speed < -1 || options.speed > 10)
    return Status(ErrorCode::invalid_argument, what + ": Draco options out of range");
  const uint32_t n = static_cast<uint32_t>(in.vertex_count());
  draco::Mesh mesh;
  mesh.set_num_points(n);
  draco::GeometryAttribute ga;
  ga.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
  const int att = mesh.AddAttribute(ga, /*identity_mapping=*/true, n);
  for (uint32_t v = 0; v < n; ++v)
    mesh.attribute(att)->SetAttributeValue(draco::AttributeValueIndex(v), &in.positions[3 * size_t{v}]);
  for (size_t f = 0; f < in.triangle_count(); ++f) {
    draco::Mesh::Face face;
    for (int k = 0; k < 3; ++k) {
      const uint32_t i = in.triangles[3 * f + k];
      if (i >= n) return Status(ErrorCode::invalid_argument, what + ": triangle " + std::to_string(f) + " names a missing vertex");
      face[k] = draco::PointIndex(i);
    }
    mesh.AddFace(face);
  }
  draco::Encoder encoder;
  if (options.position_bits > 0) encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, options.position_bits);
  if (options.speed >= 0) encoder.SetSpeedOptions(options.speed, options.speed);
  draco::EncoderBuffer buffer;
  if (const draco::Status s = encoder.EncodeMeshToBuffer(mesh, &buffer); !s.ok())
    return Status(ErrorCode::internal, what + ": Draco encoder: " + s.error_msg_string());
  return std::vector<uint8_t>(buffer.data(), buffer.data() + buffer.size());
}

}  // namespace dbss::io
