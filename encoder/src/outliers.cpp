#include "dbss/encoder/outliers.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "dbss/encoder/mesh_ops.h"

namespace dbss {

namespace {

// Union-find with path halving; ids stay below 2^32 (point counts do).
struct Sets {
  std::vector<uint32_t> parent;
  explicit Sets(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t find(uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(uint32_t a, uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

size_t used_count(const std::vector<uint32_t>& neighbours, size_t i, uint32_t k) {
  return static_cast<size_t>(std::count_if(neighbours.begin() + i * k, neighbours.begin() + (i + 1) * k,
                                           [](uint32_t j) { return j != UINT32_MAX; }));
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  return v[mid];
}

PointCloud subset(const PointCloud& pc, const std::vector<uint8_t>& keep) {
  PointCloud out;
  const bool normals = pc.normals.size() == pc.xyz.size();
  for (size_t i = 0; i < pc.size(); ++i) {
    if (!keep[i]) continue;
    out.xyz.insert(out.xyz.end(), &pc.xyz[3 * i], &pc.xyz[3 * i + 3]);
    if (normals) out.normals.insert(out.normals.end(), &pc.normals[3 * i], &pc.normals[3 * i + 3]);
  }
  return out;
}

}  // namespace

std::vector<uint32_t> point_clusters(const PointIndex& index, double radius, uint32_t* count) {
  const PointCloud& pc = index.points();
  const size_t n = pc.size();
  Sets sets(n);
  std::vector<uint32_t> near;
  for (size_t i = 0; i < n; ++i) {
    index.within(&pc.xyz[3 * i], static_cast<float>(radius), near);
    for (uint32_t j : near) sets.join(static_cast<uint32_t>(i), j);
  }
  // Roots are each cluster's smallest point, so numbering roots in point
  // order gives ids in order of first point.
  std::vector<uint32_t> id(n), root_id(n, UINT32_MAX);
  uint32_t c = 0;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t r = sets.find(static_cast<uint32_t>(i));
    if (root_id[r] == UINT32_MAX) root_id[r] = c++;
    id[i] = root_id[r];
  }
  if (count) *count = c;
  return id;
}

double cluster_radius(const PointIndex& index, const OutlierOptions& o) { return o.link * point_spacing(index, 1, 0.99); }

PointCloud remove_outliers(const PointIndex& index, const OutlierOptions& o, OutlierStats* stats) {
  const PointCloud& pc = index.points();
  const size_t n = pc.size();
  OutlierStats s;
  s.points_in = n;
  if (stats) *stats = s;
  const uint32_t k = std::max<uint32_t>(1, o.k);
  if (!o.enabled || n <= size_t{k} + 4) return pc;

  // Mean distance to the k nearest other points, for every point.
  std::vector<double> reach(n);
  // Flat k-per-point neighbour lists (UINT32_MAX where fewer were found).
  std::vector<uint32_t> neighbours(n * k, UINT32_MAX);
  std::vector<uint32_t> idx(k + 1);
  std::vector<float> d2(k + 1);
  for (size_t i = 0; i < n; ++i) {
    const size_t got = index.nearest_k(&pc.xyz[3 * i], k + 1, idx.data(), d2.data());
    double sum = 0;
    size_t used = 0;
    // The first hit is the point itself (or a duplicate of it): skip one.
    for (size_t j = 1; j < got; ++j) {
      sum += std::sqrt(double{d2[j]});
      ++used;
      neighbours[i * k + j - 1] = idx[j];
    }
    reach[i] = used ? sum / used : 0;
  }
  std::vector<uint8_t> keep(n, 1);
  std::vector<double> around;
  for (size_t i = 0; i < n; ++i) {
    around.clear();
    for (size_t j = i * k; j < (i + 1) * k; ++j)
      if (neighbours[j] != UINT32_MAX) around.push_back(reach[neighbours[j]]);
    const double local = median(around);
    if (!(local > 0)) continue;
    bool isolated = reach[i] > o.isolation * local;
    if (!isolated && used_count(neighbours, i, k) >= 5) {
      // Near the surface a stray point still has surface points for
      // neighbours, at a few spacings: it stands off their plane, where a
      // surface point (even at a crease or on a thin wall) lies close to it.
      uint32_t ids[64];
      size_t m = 0;
      for (size_t j = i * k; j < (i + 1) * k && m < 64; ++j)
        if (neighbours[j] != UINT32_MAX) ids[m++] = neighbours[j];
      const PointPlane plane = fit_plane(pc, ids, m);
      double off = 0;
      for (int a = 0; a < 3; ++a) off += (pc.xyz[3 * i + a] - plane.point[a]) * plane.normal[a];
      isolated = std::abs(off) > o.off_plane * local;
    }
    if (isolated) {
      keep[i] = 0;
      ++s.isolated;
    }
  }

  // Clusters among the points left.
  PointCloud rest = subset(pc, keep);
  if (rest.size() > k) {
    const PointIndex rest_index(rest);
    uint32_t count = 0;
    const std::vector<uint32_t> cluster = point_clusters(rest_index, cluster_radius(rest_index, o), &count);
    std::vector<size_t> size(count, 0);
    for (uint32_t c : cluster) ++size[c];
    s.clusters = count;
    const double min_size = o.min_cluster_share * static_cast<double>(rest.size());
    size_t r = 0;
    for (size_t i = 0; i < n; ++i) {
      if (!keep[i]) continue;
      if (static_cast<double>(size[cluster[r]]) < min_size) {
        keep[i] = 0;
        ++s.cluster_points;
      }
      ++r;
    }
    for (size_t c = 0; c < count; ++c) s.clusters_dropped += static_cast<double>(size[c]) < min_size;
  }
  if (s.kept() < 4) {
    // Nothing sane is left: keep everything and let the caller's checks speak.
    s.isolated = s.cluster_points = s.clusters_dropped = 0;
    if (stats) *stats = s;
    return pc;
  }
  if (stats) *stats = s;
  return subset(pc, keep);
}

}  // namespace dbss
