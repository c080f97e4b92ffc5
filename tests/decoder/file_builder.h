// Builds .dbss files for decoder tests from a mesh and pseudo-random
// displacements, the way the encoder will: continuing from the Draco-decoded
// control mesh.
#pragma once

#include <cstdint>
#include <vector>

#include "dbss/decoder/control_mesh.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/control_mesh_codec.h"
#include "dbss/format/writer.h"
#include "../crease_shapes.h"

namespace dbss::test {

// With `crease_degrees` > 0, the control mesh's edges whose dihedral angle
// is over it are tagged (creases_from_dihedral): a version 1.1 file.  With
// `context`, every level is coded with coding 2: a version 1.2 file.  With
// `boundary_amplitude` > 0 (a mesh with a boundary), every level also has
// boundary values in -amplitude..amplitude, in codings 1, 2, 0 by level: a
// version 1.3 file.
inline std::vector<uint8_t> build_file(const TriangleMesh& mesh, uint8_t levels, int32_t amplitude, float step,
                                       uint32_t seed = 1, double crease_degrees = 0, bool context = false,
                                       int32_t boundary_amplitude = 0) {
  auto draco = encode_control_mesh(mesh, {});
  auto decoded = decode_control_mesh(draco.value(), 1 << 24, 1 << 24);
  auto topo = build_topology(static_cast<uint32_t>(decoded.value().vertex_count()), decoded.value().triangles);
  format::FileContents c;
  c.header.level_count = levels;
  c.header.control_position_bits = 16;
  c.header.control_vertex_count = static_cast<uint32_t>(decoded.value().vertex_count());
  c.header.control_edge_count = topo.value().edge_count();
  c.header.control_triangle_count = static_cast<uint32_t>(decoded.value().triangle_count());
  c.header.bbox_min = {-2, -2, -2};
  c.header.bbox_max = {2, 2, 2};
  c.control_mesh = std::move(draco).value();
  if (crease_degrees > 0) {
    c.creases = creases_from_dihedral(decoded.value(), crease_degrees);
    c.header.version_minor = format::kCreaseVersionMinor;
  }
  const format::MeshCounts control{c.header.control_vertex_count, c.header.control_edge_count,
                                   c.header.control_triangle_count};
  uint32_t s = seed * 747796405u + 2891336453u;
  for (uint8_t l = 1; l <= levels; ++l) {
    format::Level level;
    level.index = l;
    level.step = step / static_cast<float>(1 << l);
    level.coding = context ? format::DisplacementCoding::context
                   : l % 2 ? format::DisplacementCoding::byte_planes
                           : format::DisplacementCoding::varint;
    level.q.resize(*format::odd_vertex_count(control, l));
    for (auto& q : level.q) {
      s = s * 1664525u + 1013904223u;
      q = amplitude ? static_cast<int32_t>((s >> 8) % (2 * uint32_t(amplitude) + 1)) - amplitude : 0;
    }
    if (boundary_amplitude > 0) {
      level.boundary.step = 0.75f * level.step;
      level.boundary.coding = static_cast<format::DisplacementCoding>(l % 3 == 1 ? 1 : l % 3 == 2 ? 2 : 0);
      level.boundary.q.resize(*format::boundary_edge_count(control, l - 1u));
      for (auto& q : level.boundary.q) {
        s = s * 1664525u + 1013904223u;
        q = static_cast<int32_t>((s >> 8) % (2 * uint32_t(boundary_amplitude) + 1)) - boundary_amplitude;
      }
    }
    c.levels.push_back(std::move(level));
  }
  c.header.version_minor = format::minimum_version_minor(c);
  return format::serialize(c).value();
}

// FNV-1a 64 over the bit patterns of a float array (spec/decoding.md
// section 8's level hash on a little-endian host): bit-exact comparisons.
inline uint64_t hash_floats(const float* p, size_t n) {
  uint64_t h = 14695981039346656037ull;
  const auto* b = reinterpret_cast<const uint8_t*>(p);
  for (size_t i = 0; i < 4 * n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  return h;
}

}  // namespace dbss::test
