// Draco compression of one level for KHR_draco_mesh_compression: encode,
// then decode the bytes once to learn what a viewer will get back (Draco
// may reorder and merge points, and quantizes them), since the glTF
// accessors must state those counts and bounds.
#include "gltf_draco.h"

#include "dbss/io/draco_mesh.h"

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>

#include <algorithm>
#include <limits>
#include <string>
#include <utility>

namespace dbss::io_detail {

Result<DracoLevel> draco_level(const TriangleMesh& in, int bits) {
  if (bits < 1 || bits > 30) return Status(ErrorCode::invalid_argument, "glTF: Draco position bits must be 1 to 30");
  auto bytes = io::draco_encode(in, {bits, -1}, "glTF level");
  if (!bytes.ok()) return bytes.status();
  DracoLevel out;
  out.bytes = std::move(bytes).value();
  draco::DecoderBuffer db;
  db.Init(reinterpret_cast<const char*>(out.bytes.data()), out.bytes.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&db);
  if (!decoded.ok()) return Status(ErrorCode::internal, "glTF: Draco cannot decode its own level: " + decoded.status().error_msg_string());
  const draco::Mesh& d = *decoded.value();
  const draco::PointAttribute* pos = d.GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (pos == nullptr) return Status(ErrorCode::internal, "glTF: Draco's decoded level has no positions");
  out.points = d.num_points();
  out.faces = d.num_faces();
  out.position_id = static_cast<int>(pos->unique_id());
  for (int a = 0; a < 3; ++a) {
    out.min[a] = std::numeric_limits<double>::infinity();
    out.max[a] = -std::numeric_limits<double>::infinity();
  }
  for (draco::PointIndex p(0); p < d.num_points(); ++p) {
    float xyz[3];
    pos->GetMappedValue(p, xyz);
    for (int a = 0; a < 3; ++a) {
      out.min[a] = std::min(out.min[a], double{xyz[a]});
      out.max[a] = std::max(out.max[a], double{xyz[a]});
    }
  }
  return out;
}

}  // namespace dbss::io_detail
