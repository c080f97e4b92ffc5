#include "dbss/encoder/crease_lines.h"

#include <algorithm>
#include <cmath>

#include "dbss/decoder/topology.h"
#include "mesh_geometry.h"

namespace dbss {

CreaseLines::CreaseLines(const TriangleMesh& control, const format::Creases& creases, const PointIndex& points,
                         double slack, size_t neighbourhood) {
  if (creases.edge.empty()) return;
  auto topology = build_topology(static_cast<uint32_t>(control.vertex_count()), control.triangles);
  if (!topology.ok()) return;
  const LevelTopology& t = topology.value();
  if (creases.edge.size() != t.edge_count()) return;
  std::vector<uint32_t> near(neighbourhood);
  std::vector<float> dist2(neighbourhood);
  double longest = 0;
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    if (!creases.edge[e]) continue;
    const uint32_t h = t.edge_half[e], u = t.triangles[h], w = t.triangles[next_half(h)];
    Segment s;
    float mid[3];
    double len2 = 0;
    for (int k = 0; k < 3; ++k) {
      s.a[k] = control.positions[3 * size_t{u} + k], s.b[k] = control.positions[3 * size_t{w} + k];
      mid[k] = static_cast<float>(0.5 * (s.a[k] + s.b[k]));
      len2 += (s.b[k] - s.a[k]) * (s.b[k] - s.a[k]);
    }
    const size_t found = neighbourhood ? points.nearest_k(mid, neighbourhood, near.data(), dist2.data()) : 0;
    s.reach = slack * std::sqrt(len2) + (found ? std::sqrt(double{dist2[found - 1]}) : 0.0);
    longest = std::max(longest, std::sqrt(len2) + 2 * s.reach);
    segments_.push_back(s);
  }
  if (segments_.empty() || !(longest > 0)) {
    segments_.clear();
    return;
  }
  // Cells the size of the longest segment with its reach: each segment is
  // listed in every cell its reach's box touches (a few), a query looks in
  // its own cell only.
  cell_ = longest;
  for (uint32_t i = 0; i < segments_.size(); ++i) {
    const Segment& s = segments_[i];
    int64_t lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = static_cast<int64_t>(std::floor((std::min(s.a[k], s.b[k]) - s.reach) / cell_));
      hi[k] = static_cast<int64_t>(std::floor((std::max(s.a[k], s.b[k]) + s.reach) / cell_));
    }
    for (int64_t x = lo[0]; x <= hi[0]; ++x)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for (int64_t z = lo[2]; z <= hi[2]; ++z) grid_[cell_key(x, y, z)].push_back(i);
  }
}

uint64_t CreaseLines::cell_key(int64_t x, int64_t y, int64_t z) const {
  // 21 bits per axis: a model spans a few cells of its longest crease edge.
  const auto b = [](int64_t v) { return static_cast<uint64_t>(v) & 0x1FFFFF; };
  return b(x) | b(y) << 21 | b(z) << 42;
}

bool CreaseLines::near(const double p[3]) const {
  if (segments_.empty()) return false;
  const auto it = grid_.find(cell_key(static_cast<int64_t>(std::floor(p[0] / cell_)), static_cast<int64_t>(std::floor(p[1] / cell_)),
                                      static_cast<int64_t>(std::floor(p[2] / cell_))));
  if (it == grid_.end()) return false;
  using mesh_geometry::V3;
  for (uint32_t i : it->second) {
    const Segment& g = segments_[i];
    const double d2 = mesh_geometry::distance2_to_segment(V3{p[0], p[1], p[2]}, V3{g.a[0], g.a[1], g.a[2]}, V3{g.b[0], g.b[1], g.b[2]});
    if (d2 <= g.reach * g.reach) return true;
  }
  return false;
}

}  // namespace dbss
