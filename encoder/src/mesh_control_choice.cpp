#include "mesh_control_choice.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "control_choice.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/triangle_tree.h"

namespace dbss {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Centroid and area of triangle t of (positions, triangles).
double centroid_area(const std::vector<float>& positions, const std::vector<uint32_t>& triangles, size_t t, double c[3]) {
  const float* p[3];
  for (int k = 0; k < 3; ++k) p[k] = &positions[3 * size_t{triangles[3 * t + k]}];
  double u[3], v[3];
  for (int a = 0; a < 3; ++a) {
    c[a] = (double{p[0][a]} + p[1][a] + p[2][a]) / 3;
    u[a] = double{p[1][a]} - p[0][a];
    v[a] = double{p[2][a]} - p[0][a];
  }
  const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
  return 0.5 * std::sqrt(x * x + y * y + z * z);
}

// Area-weighted mean of `distance` over (a stride of) the triangles' centroids.
template <class Distance>
double mean_from_centroids(const std::vector<float>& positions, const std::vector<uint32_t>& triangles, Distance distance) {
  const size_t n = triangles.size() / 3, m = std::min(n, kMeshChoiceProbe);
  double sum = 0, area = 0;
  for (size_t s = 0; s < m; ++s) {
    double c[3];
    const double a = centroid_area(positions, triangles, s * n / m, c);
    sum += a * distance(c);
    area += a;
  }
  return area > 0 ? sum / area : 0.0;
}

std::string describe(const std::vector<RdPoint>& curve, double diagonal) {
  std::string s;
  char buf[48];
  for (const RdPoint& p : curve)
    std::snprintf(buf, sizeof buf, "%s%.1f KB %.3g", s.empty() ? "" : ", ", p.bytes / 1000, p.error / diagonal), s += buf;
  return s;
}

// The (prefix bytes, distance to the input) of a serialized encoding's
// levels, from the last one down to the first whose distance is above
// `error` (or level 0): the part of its curve that can reach `error`.
// Measuring a level costs a tree over its triangles, so the coarser levels
// the comparison cannot use are left out.
std::vector<RdPoint> mesh_rd_curve_down_to(const Encoding& e, const TriangleMesh& input, const MeshSurface& surface, double error) {
  std::vector<RdPoint> curve;
  for (uint32_t l = e.level_count + 1; l-- > 0;) {
    curve.insert(curve.begin(), RdPoint{static_cast<double>(prefix_bytes(e, l)),
                                        level_distance_to_mesh(e.levels.positions[l], e.levels.triangles[l], surface, input)});
    if (curve.front().error > error) break;
  }
  return curve;
}

}  // namespace

double level_distance_to_mesh(const std::vector<float>& positions, const std::vector<uint32_t>& triangles,
                              const MeshSurface& input_surface, const TriangleMesh& input) {
  double out[3];
  const double to_input =
      mean_from_centroids(positions, triangles, [&](const double c[3]) { return input_surface.closest_point(c, out); });
  // The input's probes to the level, exactly, without a bounding-volume
  // tree over the level: building one over the last level (804k triangles
  // on bunny00's level 4) was most of the choice's cost on every file.  A
  // KD-tree over the level's centroids gives each probe a first triangle
  // and its distance d; any triangle nearer than d has its centroid within
  // d + (the largest centroid-to-corner distance), so only those are
  // measured.
  const size_t n = triangles.size() / 3;
  PointCloud centroids;
  centroids.xyz.resize(3 * n);
  double reach = 0;
  for (size_t t = 0; t < n; ++t) {
    double c[3];
    (void)centroid_area(positions, triangles, t, c);
    for (int a = 0; a < 3; ++a) centroids.xyz[3 * t + a] = static_cast<float>(c[a]);
    for (int k = 0; k < 3; ++k) {
      const float* p = &positions[3 * size_t{triangles[3 * t + k]}];
      double d2 = 0;
      for (int a = 0; a < 3; ++a) d2 += (p[a] - double{centroids.xyz[3 * t + a]}) * (p[a] - double{centroids.xyz[3 * t + a]});
      reach = std::max(reach, std::sqrt(d2));
    }
  }
  if (n == 0) return std::numeric_limits<double>::infinity();
  const PointIndex index(centroids);
  const auto triangle_distance = [&](const double q[3], uint32_t t) {
    double corner[3][3];
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) corner[k][a] = positions[3 * size_t{triangles[3 * size_t{t} + k]} + a];
    return std::sqrt(point_triangle_distance2(q, corner[0], corner[1], corner[2]));
  };
  std::vector<uint32_t> near;
  const double to_level = mean_from_centroids(input.positions, input.triangles, [&](const double c[3]) {
    const float q[3] = {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])};
    double best = triangle_distance(c, index.nearest(q));
    // A little over, for the centroids' and the query's rounding to float.
    const double radius = (best + reach) * (1 + 1e-5) + 1e-30;
    index.within(q, static_cast<float>(radius), near);
    for (uint32_t t : near) best = std::min(best, triangle_distance(c, t));
    return best;
  });
  return 0.5 * (to_input + to_level);
}

void choose_mesh_control(Encoding& e, MeshControlStats& stats, uint32_t faces, const TriangleMesh& input,
                         const MeshSurface& surface, const MeshControlEncoder& encode, const MeshControlChoiceOptions& o) {
  const auto t = Clock::now();
  const auto stage_seconds = [](const Encoding& x) {
    return x.seconds.control + x.seconds.draco + x.seconds.levels + x.seconds.serialize;
  };
  const double default_work = stage_seconds(e);
  const uint32_t last = e.level_count;
  const double target = e.error * e.diagonal;
  const double floor = level_distance_to_mesh(e.levels.positions[last], e.levels.triangles[last], surface, input);
  const double ratio = target > 0 ? floor / target : 0.0;
  char head[160];
  std::snprintf(head, sizeof head, "%u faces: level %u at %.3g of the diagonal, %.2fx the target", faces, last,
                floor / e.diagonal, ratio);
  if (!(ratio >= o.floor_ratio) || last == 0) {
    // Said briefly: every file not floor-bound carries it in `meta`.
    char why[160];
    std::snprintf(why, sizeof why, "kept the default, %u faces: level %u at %.2fx the target, not floor-bound (under %.2fx)",
                  faces, last, ratio, o.floor_ratio);
    e.control_choice = why;
    e.seconds.choice = since(t);
    return;
  }
  const uint32_t larger = static_cast<uint32_t>(o.scale * faces) & ~1u;
  Encoding candidate;
  MeshControlStats candidate_stats;
  if (Status st = encode(larger, candidate, candidate_stats); !st.ok()) {
    e.control_choice = "kept the default, " + std::string(head) + " (floor-bound; " + std::to_string(larger) +
                       " faces failed: " + st.to_string() + ")";
    e.seconds.choice = since(t);
    return;
  }
  const RdPoint reached{static_cast<double>(prefix_bytes(e, last)), floor};
  const std::vector<RdPoint> fine = mesh_rd_curve_down_to(candidate, input, surface, kRdTolerance * floor);
  const bool keep = rd_curve_dominates(fine, {reached});
  const std::string versus = std::string(head) + ", floor-bound: " + std::to_string(larger) + " faces (levels " +
                             std::to_string(last + 1 - fine.size()) + "-" + std::to_string(last) + ": " +
                             describe(fine, e.diagonal) + ") against its level " + std::to_string(last) + " (" +
                             describe({reached}, e.diagonal) + ")";
  const double seconds = since(t);
  if (keep) {
    e = std::move(candidate);
    stats = candidate_stats;
    e.control_choice = "kept the larger control mesh over " + versus;
  } else {
    e.control_choice = "kept the default, " + versus;
  }
  // Kept, the candidate's own stages are in e.seconds and the default's
  // (which ran before `t`) are what the choice cost.
  e.seconds.choice = keep ? seconds - stage_seconds(e) + default_work : seconds;
}

}  // namespace dbss
