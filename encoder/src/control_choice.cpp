#include "control_choice.h"

#include <algorithm>
#include <cmath>

#include "dbss/encoder/point_distances.h"
#include "dbss/encoder/triangle_tree.h"

namespace dbss {

// Mean distance from (a stride of) the points to the level's triangles and
// from (a stride of) its vertices to the least-squares plane of their 8
// nearest points, averaged: two-sided, like the benchmark's error against
// the true surface, since one side alone is fooled (a surface that wiggles
// through every point is near all of them; the vertices of one that cuts
// corners are near the points' planes).
double level_distance_to_points(const std::vector<float>& positions, const std::vector<uint32_t>& triangles,
                                const PointIndex& index, bool area_weighted) {
  const PointCloud& pc = index.points();
  const TriangleMesh level{positions, triangles};
  const TriangleTree tree(level);
  const size_t n = pc.size(), m = std::min(n, kRdProbe);
  double to_level = 0;
  for (size_t s = 0; s < m; ++s) {
    const size_t i = s * n / m;
    const double p[3] = {pc.xyz[3 * i], pc.xyz[3 * i + 1], pc.xyz[3 * i + 2]};
    to_level += tree.distance(p);
  }
  const size_t v = positions.size() / 3, k = std::min(v, kRdProbe);
  if (area_weighted) {
    std::vector<double> area(v, 0.0);
    for (size_t f = 0; f + 2 < triangles.size(); f += 3) {
      const float* a = &positions[3 * size_t{triangles[f]}];
      const float* b = &positions[3 * size_t{triangles[f + 1]}];
      const float* c = &positions[3 * size_t{triangles[f + 2]}];
      const double u[3] = {double{b[0]} - a[0], double{b[1]} - a[1], double{b[2]} - a[2]};
      const double w[3] = {double{c[0]} - a[0], double{c[1]} - a[1], double{c[2]} - a[2]};
      const double x = u[1] * w[2] - u[2] * w[1], y = u[2] * w[0] - u[0] * w[2], z = u[0] * w[1] - u[1] * w[0];
      const double third = std::sqrt(x * x + y * y + z * z) / 6;
      for (int j = 0; j < 3; ++j) area[triangles[f + j]] += third;
    }
    uint32_t near[8];
    float d2[8];
    double sum = 0, weight = 0;
    for (size_t s = 0; s < k; ++s) {
      const size_t i = s * v / k;
      const size_t found = index.nearest_k(&positions[3 * i], 8, near, d2);
      const PointPlane plane = fit_plane(pc, near, found);
      double dist = 0;
      for (int j = 0; j < 3; ++j) dist += (double{positions[3 * i + j]} - plane.point[j]) * plane.normal[j];
      sum += area[i] * std::abs(dist);
      weight += area[i];
    }
    const double to_points = weight > 0 ? sum / weight : 0;
    return 0.5 * (to_level / static_cast<double>(std::max<size_t>(m, 1)) + to_points);
  }
  std::vector<float> probe;
  probe.reserve(3 * k);
  for (size_t s = 0; s < k; ++s) probe.insert(probe.end(), &positions[3 * (s * v / k)], &positions[3 * (s * v / k)] + 3);
  const double to_points = vertices_to_points_surface(probe, index).mean;
  return 0.5 * (to_level / static_cast<double>(std::max<size_t>(m, 1)) + to_points);
}

std::vector<RdPoint> encoder_rd_curve(const Encoding& e, const PointIndex& index, bool area_weighted) {
  std::vector<RdPoint> curve;
  const size_t points = index.points().size();
  double bytes = static_cast<double>(e.contents.control_mesh.size());
  for (size_t l = 0; l < e.levels.positions.size(); ++l) {
    if (l > 0) {
      // Past the crossing level every q is 0 (dead_zone_steps): stop.
      if (e.levels.positions[l - 1].size() / 3 > points) break;
      bytes += static_cast<double>(e.levels.chunks[l - 1].size());
    }
    curve.push_back({bytes, level_distance_to_points(e.levels.positions[l], e.levels.triangles[l], index, area_weighted), e.levels.positions[l].size() / 3});
  }
  return curve;
}

bool rd_curve_dominates(const std::vector<RdPoint>& coarse, const std::vector<RdPoint>& fine) {
  for (const RdPoint& f : fine) {
    const double target = kRdTolerance * f.error;
    double reached = -1;
    for (size_t i = 0; i < coarse.size() && reached < 0; ++i) {
      if (!(coarse[i].error <= target)) continue;
      if (i == 0) {
        reached = coarse[0].bytes;
        break;
      }
      const RdPoint& p = coarse[i - 1];
      const RdPoint& r = coarse[i];
      // A zero error (an exact fit) has no logarithm: take the level's bytes.
      if (!(r.error > 0 && p.error > 0)) {
        reached = r.bytes;
        break;
      }
      const double t = (std::log(target) - std::log(p.error)) / (std::log(r.error) - std::log(p.error));
      reached = std::exp(std::log(p.bytes) + t * (std::log(r.bytes) - std::log(p.bytes)));
    }
    if (!(reached >= 0 && reached <= f.bytes)) return false;  // NaN fails too
  }
  return true;
}

bool keep_coarse_control(const std::vector<RdPoint>& coarse, const std::vector<RdPoint>& fine, bool noisy, size_t points) {
  if (!noisy) return rd_curve_dominates(coarse, fine);
  std::vector<RdPoint> targets;
  for (const RdPoint& f : fine)
    if (f.vertices <= points) targets.push_back(f);
  // (Level 0 alone past the density: nothing before the noise to compare.)
  // The coarse curve keeps all its levels on purpose: its own crossing level
  // may still reach a target of the fine curve's earlier levels, and if it
  // does, that is bytes the user would spend anyway at that error.
  if (targets.empty()) return rd_curve_dominates(coarse, fine);
  return rd_curve_dominates(coarse, targets);
}

int fewest_control_bits(int kept_bits, const std::vector<RdPoint>& kept, const std::vector<BitsCurve>& candidates) {
  int best = kept_bits;
  for (const BitsCurve& c : candidates)
    if (c.bits < best && rd_curve_dominates(c.curve, kept)) best = c.bits;
  return best;
}

}  // namespace dbss
