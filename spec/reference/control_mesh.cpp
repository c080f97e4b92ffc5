// decoding.md section 2: level 0 from the CTRL chunk's Draco payload.
#include "control_mesh.h"

#include <draco/compression/decode.h>

#include <cmath>

#include "topology.h"

namespace dbss_ref::detail {

std::string control_mesh(std::span<const uint8_t> payload, uint32_t V0, uint32_t E0, uint32_t F0,
                         Mesh& out) {
  // Step 1: a Draco mesh decoder.
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(payload.data()), payload.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok() || !decoded.value()) return "compression";
  const draco::Mesh& mesh = *decoded.value();

  // Step 2: the 3-component POSITION attribute; vertex i is value i.
  const draco::PointAttribute* pos = mesh.GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (pos == nullptr || pos->num_components() != 3) return "bad_mesh";
  const size_t V = pos->size();
  if (V != V0) return "bad_mesh";  // step 4
  out.positions.resize(3 * V);
  for (size_t i = 0; i < V; ++i) {
    float xyz[3];
    if (!pos->ConvertValue<float>(draco::AttributeValueIndex(static_cast<uint32_t>(i)), 3, xyz))
      return "bad_mesh";
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(xyz[c])) return "bad_mesh";
      out.positions[3 * i + c] = xyz[c];
    }
  }

  // Step 3: face f, point indices mapped to value indices, corner order kept.
  if (mesh.num_faces() != F0) return "bad_mesh";  // step 4
  out.triangles.resize(3 * size_t{F0});
  for (uint32_t f = 0; f < F0; ++f) {
    const auto& face = mesh.face(draco::FaceIndex(f));
    for (int k = 0; k < 3; ++k) {
      if (face[k].value() >= mesh.num_points()) return "bad_mesh";
      const uint32_t value = pos->mapped_index(face[k]).value();
      if (value >= V) return "bad_mesh";
      out.triangles[3 * size_t{f} + k] = value;
    }
  }

  // Step 5: an oriented 2-manifold with valences up to 64; step 4: E0
  // edges; step 2: every value used by some triangle.
  Topology t;
  if (!build_topology(static_cast<uint32_t>(V), out.triangles, t).empty()) return "bad_mesh";
  if (t.edge_count() != E0) return "bad_mesh";
  for (uint32_t v = 0; v < V; ++v) {
    if (t.triangles_at[v] == 0) return "bad_mesh";
    if (t.valence[v] > 64) return "bad_mesh";
    // Not in section 2, but section 5.3 defines no weights for an interior
    // vertex of valence below 3 (two triangles glued into a pillow).
    if (!t.boundary[v] && t.valence[v] < 3) return "bad_mesh";
  }
  return {};
}

}  // namespace dbss_ref::detail
