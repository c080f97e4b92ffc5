#include "dbss/format/container.h"

namespace dbss::format {

bool ChunkType::well_formed() const noexcept {
  for (char ch : c)
    if (!((ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z'))) return false;
  return true;
}

std::optional<MeshCounts> counts_at_level(const MeshCounts& control, uint32_t level) {
  // Any count below 2^62 keeps 2E + 3F and 4F below 2^64 for one more step.
  constexpr uint64_t kCap = uint64_t{1} << 62;
  MeshCounts m = control;
  if (m.vertices >= kCap || m.edges >= kCap || m.triangles >= kCap) return std::nullopt;
  for (uint32_t l = 0; l < level; ++l) {
    MeshCounts n{m.vertices + m.edges, 2 * m.edges + 3 * m.triangles, 4 * m.triangles};
    if (n.vertices >= kCap || n.edges >= kCap || n.triangles >= kCap) return std::nullopt;
    m = n;
  }
  return m;
}

std::optional<uint64_t> odd_vertex_count(const MeshCounts& control, uint32_t level) {
  if (level == 0) return std::nullopt;
  auto prev = counts_at_level(control, level - 1);
  if (!prev) return std::nullopt;
  return prev->edges;
}

std::optional<uint64_t> boundary_edge_count(const MeshCounts& control, uint32_t level) {
  auto c = counts_at_level(control, level);
  if (!c || 2 * c->edges < 3 * c->triangles) return std::nullopt;  // no overflow: both are below 2^62
  return 2 * c->edges - 3 * c->triangles;
}

}  // namespace dbss::format
