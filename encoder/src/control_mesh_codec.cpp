#include "dbss/encoder/control_mesh_codec.h"

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace dbss {

int control_bits_for_step(const TriangleMesh& mesh, float step) {
  if (mesh.vertex_count() == 0 || !(step > 0)) return 16;
  float lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = hi[a] = mesh.positions[a];
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    for (int a = 0; a < 3; ++a)
      lo[a] = std::min(lo[a], mesh.positions[3 * v + a]), hi[a] = std::max(hi[a], mesh.positions[3 * v + a]);
  const double extent = std::max({double{hi[0]} - lo[0], double{hi[1]} - lo[1], double{hi[2]} - lo[2]});
  if (!(extent > 0)) return 16;
  // Draco's quantization rounds to within half of extent / 2^bits.
  return static_cast<int>(std::clamp(std::ceil(std::log2(extent / step)), 8.0, 16.0));
}

Result<std::vector<uint8_t>> encode_control_mesh(const TriangleMesh& in, const ControlCodecOptions& options) {
  if (in.positions.size() % 3 != 0 || in.triangles.size() % 3 != 0 || in.triangle_count() == 0)
    return Status(ErrorCode::invalid_argument, "control mesh: positions or triangles are not whole triples");
  if (options.position_bits < 0 || options.position_bits > 30 || options.speed < 0 || options.speed > 10)
    return Status(ErrorCode::invalid_argument, "control mesh: Draco options out of range");
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
      if (i >= n) return Status(ErrorCode::invalid_argument, "control mesh: triangle " + std::to_string(f) + " names a missing vertex");
      face[k] = draco::PointIndex(i);
    }
    mesh.AddFace(face);
  }
  draco::Encoder encoder;
  if (options.position_bits > 0)
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, options.position_bits);
  encoder.SetSpeedOptions(options.speed, options.speed);
  draco::EncoderBuffer buffer;
  const draco::Status s = encoder.EncodeMeshToBuffer(mesh, &buffer);
  if (!s.ok()) return Status(ErrorCode::internal, "control mesh: Draco encoder: " + s.error_msg_string());
  return std::vector<uint8_t>(buffer.data(), buffer.data() + buffer.size());
}

}  // namespace dbss
