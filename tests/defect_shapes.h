// Defective scans of known shapes (issue 13): the clean samples of
// sampled_shapes.h with the faults real scans have — stray points, a hole
// where the scanner did not reach, only one side of the object, a near side
// denser than the far side, noise.  Every generator is deterministic for a
// given seed and keeps the input order of the points it keeps (normals kept
// along when the cloud has them), so tests can tell the clean points apart.
// Also the figures the tests and bench/scan_bench.cpp measure a result by:
// the points' median spacing and a mesh's components, genus and boundary
// loops (open surfaces included, which mesh_info() does not count).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <numbers>
#include <queue>
#include <random>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/point_input.h"
#include "sampled_shapes.h"

namespace dbss::test {

using Vec3 = std::array<double, 3>;

inline Vec3 normalized(Vec3 v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (n > 0)
    for (double& c : v) c /= n;
  return v;
}

struct Bounds {
  Vec3 lo{0, 0, 0}, hi{0, 0, 0};
  Vec3 centre() const { return {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])}; }
  double diagonal() const {
    return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                     (hi[2] - lo[2]) * (hi[2] - lo[2]));
  }
};

inline Bounds bounds(const PointCloud& c) {
  Bounds b;
  if (c.size() == 0) return b;
  for (int a = 0; a < 3; ++a) b.lo[a] = b.hi[a] = c.xyz[a];
  for (size_t i = 0; i < c.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = std::min(b.lo[a], double{c.xyz[3 * i + a]});
      b.hi[a] = std::max(b.hi[a], double{c.xyz[3 * i + a]});
    }
  return b;
}

// The points for which keep(i) holds, in input order.
inline PointCloud keep_points(const PointCloud& c, const std::function<bool(size_t)>& keep) {
  PointCloud out;
  const bool normals = c.normals.size() == c.xyz.size();
  for (size_t i = 0; i < c.size(); ++i) {
    if (!keep(i)) continue;
    out.xyz.insert(out.xyz.end(), c.xyz.begin() + 3 * i, c.xyz.begin() + 3 * i + 3);
    if (normals) out.normals.insert(out.normals.end(), c.normals.begin() + 3 * i, c.normals.begin() + 3 * i + 3);
  }
  return out;
}

// The points' median distance to their nearest point (the encoder's own
// figure: point_spacing(index, 1, 0.5), over up to 4096 points).
inline double median_spacing(const PointCloud& c) {
  if (c.size() < 2) return 0;
  const PointIndex index(c);
  return point_spacing(index, 1, 0.5);
}

// The surface area each point stands for, up to a common factor: the area
// of the disk out to its k-th nearest point, over k.  On an evenly sampled
// surface every point gets the same; on an uneven one the sparse points get
// more, so shares of this weight are shares of the area, not of the points.
inline std::vector<double> area_weights(const PointCloud& c, size_t k = 8) {
  std::vector<double> w(c.size(), 1.0);
  if (c.size() <= k) return w;
  const PointIndex index(c);
  std::vector<uint32_t> idx(k + 1);
  std::vector<float> d2(k + 1);
  for (size_t i = 0; i < c.size(); ++i) {
    const size_t got = index.nearest_k(&c.xyz[3 * i], k + 1, idx.data(), d2.data());
    w[i] = got == k + 1 ? double{d2[k]} / double(k) : 0.0;
  }
  return w;
}

// The cut value over `key` (one per point) above which the points hold
// `share` of the total weight.
inline double weighted_cut(const std::vector<double>& key, const std::vector<double>& weight, double share) {
  std::vector<size_t> order(key.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return key[a] > key[b]; });
  const double total = std::accumulate(weight.begin(), weight.end(), 0.0);
  double acc = 0;
  for (size_t j = 0; j < order.size(); ++j) {
    acc += weight[order[j]];
    if (acc >= share * total) return key[order[j]];
  }
  return order.empty() ? 0.0 : key[order.back()];
}

// The cloud followed by round(share * size) outliers, uniform in the
// bounding box enlarged by 10% (5% of each side's length added at each end).
// The first cloud.size() points of the result are the clean ones.  With
// normals in the cloud, the outliers get random unit normals.
inline PointCloud with_outliers(const PointCloud& cloud, double share, uint32_t seed = 1) {
  PointCloud out = cloud;
  const Bounds b = bounds(cloud);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  const size_t count = static_cast<size_t>(std::llround(share * double(cloud.size())));
  const bool normals = cloud.normals.size() == cloud.xyz.size();
  for (size_t i = 0; i < count; ++i) {
    for (int a = 0; a < 3; ++a) {
      const double ext = b.hi[a] - b.lo[a];
      out.xyz.push_back(static_cast<float>(b.lo[a] - 0.05 * ext + 1.1 * ext * u(rng)));
    }
    if (normals) {
      const Vec3 n = normalized({g(rng), g(rng), g(rng)});
      for (double v : n) out.normals.push_back(static_cast<float>(v));
    }
  }
  return out;
}

// A hole in one place: the geodesic disk (distances along the 8-nearest-
// point graph, so the disk follows the surface and does not reach through a
// thin part) around the point farthest along `direction`, grown until it
// holds `area_share` of the surface's area (area_weights()).  On a sphere
// that is the cap (p - c)·direction > t.
inline PointCloud with_hole(const PointCloud& cloud, Vec3 direction, double area_share) {
  const size_t n = cloud.size();
  if (n < 10 || area_share <= 0) return cloud;
  direction = normalized(direction);
  size_t seed_point = 0;
  double best = -1e300;
  for (size_t i = 0; i < n; ++i) {
    const double d = direction[0] * cloud.xyz[3 * i] + direction[1] * cloud.xyz[3 * i + 1] +
                     direction[2] * cloud.xyz[3 * i + 2];
    if (d > best) best = d, seed_point = i;
  }
  // Dijkstra over the symmetric 8-nearest-point graph.
  const PointIndex index(cloud);
  constexpr size_t k = 9;  // the point itself and 8 others
  std::vector<std::vector<std::pair<uint32_t, double>>> adj(n);
  std::vector<uint32_t> idx(k);
  std::vector<float> d2(k);
  for (size_t i = 0; i < n; ++i) {
    const size_t got = index.nearest_k(&cloud.xyz[3 * i], k, idx.data(), d2.data());
    for (size_t j = 0; j < got; ++j) {
      if (idx[j] == i) continue;
      const double d = std::sqrt(double{d2[j]});
      adj[i].push_back({idx[j], d});
      adj[idx[j]].push_back({static_cast<uint32_t>(i), d});
    }
  }
  std::vector<double> dist(n, 1e300);
  using Item = std::pair<double, uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  dist[seed_point] = 0;
  queue.push({0.0, static_cast<uint32_t>(seed_point)});
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    if (d > dist[i]) continue;
    for (const auto& [j, w] : adj[i])
      if (d + w < dist[j]) {
        dist[j] = d + w;
        queue.push({dist[j], j});
      }
  }
  // Unreached points (another component) stay.
  std::vector<double> key(n);
  for (size_t i = 0; i < n; ++i) key[i] = dist[i] >= 1e300 ? std::numeric_limits<double>::lowest() : -dist[i];
  const double cut = weighted_cut(key, area_weights(cloud), area_share);
  return keep_points(cloud, [&](size_t i) { return key[i] < cut; });
}

// A slab cut: removes every point with (p - c)·direction > t, c the bounding
// box's centre, t chosen so that `area_share` of the area goes (the bottom
// of an object standing on a table: direction pointing down).
inline PointCloud with_slab_cut(const PointCloud& cloud, Vec3 direction, double area_share) {
  if (cloud.size() < 10 || area_share <= 0) return cloud;
  direction = normalized(direction);
  const Vec3 c = bounds(cloud).centre();
  std::vector<double> key(cloud.size());
  for (size_t i = 0; i < cloud.size(); ++i)
    key[i] = direction[0] * (cloud.xyz[3 * i] - c[0]) + direction[1] * (cloud.xyz[3 * i + 1] - c[1]) +
             direction[2] * (cloud.xyz[3 * i + 2] - c[2]);
  const double cut = weighted_cut(key, area_weights(cloud), area_share);
  return keep_points(cloud, [&](size_t i) { return key[i] < cut; });
}

// One side of the plane through the bounding box's centre with normal
// `normal`: the points with (p - c)·normal <= 0 (an open patch; of a sphere,
// a hemisphere with one boundary loop).
inline PointCloud half(const PointCloud& cloud, Vec3 normal = {0, 0, 1}) {
  normal = normalized(normal);
  const Vec3 c = bounds(cloud).centre();
  return keep_points(cloud, [&](size_t i) {
    return normal[0] * (cloud.xyz[3 * i] - c[0]) + normal[1] * (cloud.xyz[3 * i + 1] - c[1]) +
               normal[2] * (cloud.xyz[3 * i + 2] - c[2]) <=
           0;
  });
}

// Uneven density: each point kept with probability ratio^-s, s going from 0
// to 1 linearly across the bounding box along `axis` (0 = x, 1 = y, 2 = z;
// -1 = the longest side), so the density falls smoothly by `ratio` times
// from the low side to the high side.
inline PointCloud with_density_gradient(const PointCloud& cloud, double ratio, uint32_t seed = 1, int axis = -1) {
  const Bounds b = bounds(cloud);
  if (axis < 0 || axis > 2) {
    axis = 0;
    for (int a = 1; a < 3; ++a)
      if (b.hi[a] - b.lo[a] > b.hi[axis] - b.lo[axis]) axis = a;
  }
  const double ext = std::max(b.hi[axis] - b.lo[axis], 1e-300);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<bool> keep(cloud.size());
  for (size_t i = 0; i < cloud.size(); ++i) {
    const double s = (cloud.xyz[3 * i + axis] - b.lo[axis]) / ext;
    keep[i] = u(rng) < std::pow(ratio, -s);
  }
  return keep_points(cloud, [&](size_t i) { return keep[i]; });
}

// Gaussian noise: every coordinate moved by N(0, sigma), sigma =
// sigma_rel_to_diag times the bounding box's diagonal.
inline PointCloud with_noise(const PointCloud& cloud, double sigma_rel_to_diag, uint32_t seed = 1) {
  PointCloud out = cloud;
  const double sigma = sigma_rel_to_diag * bounds(cloud).diagonal();
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, sigma);
  for (float& v : out.xyz) v = static_cast<float>(v + g(rng));
  return out;
}

// A plate with round holes through it (issue 13: several handles that open
// at one grid of the carving's search): a box of half sides 1 x 0.7 x
// `half_thickness` with `holes` (1..5) holes of radius `radius` through it
// along z, in a row along x, zig-zagging in y.  Genus `holes`.
inline std::vector<std::array<double, 2>> plate_hole_centres(int holes) {
  std::vector<std::array<double, 2>> c;
  holes = std::clamp(holes, 1, 5);
  for (int h = 0; h < holes; ++h)
    c.push_back({holes == 1 ? 0.0 : -0.7 + 1.4 * h / (holes - 1), (h % 2 ? 0.15 : -0.15)});
  return c;
}
inline Shape holed_plate(double half_thickness, int holes, double radius) {
  const auto centres = plate_hole_centres(holes);
  Sdf sdf = [=](double x, double y, double z) {
    double d = box_sdf(x, y, z, 0, 0, 0, 1, 0.7, half_thickness);
    for (const auto& c : centres) d = std::max(d, radius - std::hypot(x - c[0], y - c[1]));
    return d;
  };
  return {"holed plate", sdf, -1.1, 1.1, 1, static_cast<int64_t>(centres.size())};
}
// The plate without its holes, scanned with gaps where they would be: the
// points within `radius` of a hole's axis removed on both faces (what a
// scan of a solid plate missing those discs on both sides gives; genus 0,
// and no wall inside the gap, where the real holes have one).
// holed_plate's points with its holes' walls sampled too: sample_sdf puts
// next to no points there (11 on a 0.2 plate's hole whose faces' density
// gives 185), where a scanner that sees through a hole scans its wall.
// `count` points go on the walls at random (the faces' density when
// count = points * wall area / face area).
inline PointCloud with_hole_walls(PointCloud plate, int holes, double radius, double half_thickness, size_t count,
                                  uint32_t seed) {
  const auto centres = plate_hole_centres(holes);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi), z(-half_thickness, half_thickness);
  for (size_t i = 0; i < count; ++i) {
    const auto& c = centres[i % centres.size()];
    const double a = angle(rng);
    for (double v : {c[0] + radius * std::cos(a), c[1] + radius * std::sin(a), z(rng)}) plate.xyz.push_back(static_cast<float>(v));
  }
  return plate;
}

inline PointCloud with_plate_gaps(const PointCloud& solid_plate, int holes, double radius) {
  const auto centres = plate_hole_centres(holes);
  return keep_points(solid_plate, [&](size_t i) {
    for (const auto& c : centres)
      if (std::hypot(solid_plate.xyz[3 * i] - c[0], solid_plate.xyz[3 * i + 1] - c[1]) < radius) return false;
    return true;
  });
}

// The sampled_shapes.h shape by name ("sphere", "torus", "double torus"...).
inline const Shape* find_shape(const std::vector<Shape>& shapes, const char* name) {
  for (const Shape& s : shapes)
    if (std::string_view(s.name) == name) return &s;
  return nullptr;
}

// The genus shape by name, built once (throws for an unknown name, which
// fails the test that asked).
inline const Shape& genus_shape(const char* name) {
  static const std::vector<Shape> shapes = genus_shapes();
  const Shape* s = find_shape(shapes, name);
  if (s == nullptr) throw std::invalid_argument(std::string("no genus shape named ") + name);
  return *s;
}

// Components, genus and boundary loops of a triangle mesh, open or closed
// (vertices no triangle uses are ignored).  genus sums over the components
// (2 - V + E - F - boundary loops) / 2.  A boundary loop is a connected set
// of boundary edges (edges in one triangle); `manifold_edges` is false when
// an edge is in more than two triangles.
struct Topology {
  uint32_t components = 0;
  int64_t genus = 0;
  uint32_t boundary_loops = 0;
  bool manifold_edges = true;
  bool closed() const { return boundary_loops == 0; }
};

inline Topology topology(const TriangleMesh& m) {
  Topology t;
  const size_t nv = m.vertex_count(), nt = m.triangle_count();
  std::vector<uint32_t> parent(nv);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  auto unite = [&](uint32_t a, uint32_t b) { parent[find(a)] = find(b); };
  std::vector<char> used(nv, 0);
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> edges;
  for (size_t f = 0; f < nt; ++f) {
    const uint32_t* v = &m.triangles[3 * f];
    for (int c = 0; c < 3; ++c) {
      used[v[c]] = 1;
      const uint32_t a = v[c], b = v[(c + 1) % 3];
      unite(a, b);
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  }
  // Per component: V, E, F and boundary loops.
  std::map<uint32_t, std::array<int64_t, 4>> comp;  // root -> V, E, F, loops
  for (uint32_t v = 0; v < nv; ++v)
    if (used[v]) ++comp[find(v)][0];
  for (size_t f = 0; f < nt; ++f) ++comp[find(m.triangles[3 * f])][2];
  std::vector<uint32_t> bparent(nv);
  std::iota(bparent.begin(), bparent.end(), 0u);
  auto bfind = [&](uint32_t x) {
    while (bparent[x] != x) x = bparent[x] = bparent[bparent[x]];
    return x;
  };
  std::vector<char> on_boundary(nv, 0);
  for (const auto& [e, count] : edges) {
    ++comp[find(e.first)][1];
    if (count > 2) t.manifold_edges = false;
    if (count == 1) {
      on_boundary[e.first] = on_boundary[e.second] = 1;
      bparent[bfind(e.first)] = bfind(e.second);
    }
  }
  for (uint32_t v = 0; v < nv; ++v)
    if (on_boundary[v] && bfind(v) == v) ++comp[find(v)][3];
  for (const auto& [root, c] : comp) {
    ++t.components;
    t.boundary_loops += static_cast<uint32_t>(c[3]);
    t.genus += (2 - (c[0] - c[1] + c[2]) - c[3]) / 2;
  }
  return t;
}

}  // namespace dbss::test
