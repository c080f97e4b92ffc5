#include "dbss/encoder/control_mesh_codec.h"

#include "dbss/io/draco_mesh.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace dbss {

namespace {

// The mesh's largest extent along an axis: what Draco's grid spans.
double largest_extent(const TriangleMesh& mesh) {
  float lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = hi[a] = mesh.positions[a];
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    for (int a = 0; a < 3; ++a)
      lo[a] = std::min(lo[a], mesh.positions[3 * v + a]), hi[a] = std::max(hi[a], mesh.positions[3 * v + a]);
  return std::max({double{hi[0]} - lo[0], double{hi[1]} - lo[1], double{hi[2]} - lo[2]});
}

// The fewest bits (8..16) whose grid, extent / 2^bits, is at most `spacing`.
int bits_for_spacing(double extent, double spacing) {
  return static_cast<int>(std::clamp(std::ceil(std::log2(extent / spacing)), 8.0, 16.0));
}

}  // namespace

int control_bits_for_step(const TriangleMesh& mesh, float step) {
  if (mesh.vertex_count() == 0 || !(step > 0)) return 16;
  const double extent = largest_extent(mesh);
  if (!(extent > 0)) return 16;
  // Draco's quantization rounds to within half of extent / 2^bits.
  return bits_for_spacing(extent, step);
}

int control_bits_for_error(const TriangleMesh& mesh, double level0_distance, float step) {
  const int by_step = control_bits_for_step(mesh, step);
  if (mesh.vertex_count() == 0 || !(level0_distance > 0) || !std::isfinite(level0_distance)) return by_step;
  const double extent = largest_extent(mesh);
  if (!(extent > 0)) return by_step;
  return std::min(by_step, bits_for_spacing(extent, kControlGridPerError * level0_distance));
}

Result<std::vector<uint8_t>> encode_control_mesh(const TriangleMesh& in, const ControlCodecOptions& options) {
  if (options.speed < 0) return Status(ErrorCode::invalid_argument, "control mesh: Draco options out of range");
  return io::draco_encode(in, {options.position_bits, options.speed}, "control mesh");
}

}  // namespace dbss
