#include "dbss/encoder/bare_handles.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "union_find.h"

namespace dbss {

namespace {

// Points whose nearest-neighbour distances make a vertex's local spacing.
constexpr size_t kLocalPoints = 8;
// Which neighbour's distance is a point's spacing.
constexpr size_t kNeighbour = 1;
// The local spacing's floor, as a share of the median spacing: samplers
// and scanners pile points on sharp edges and corners (the bench's shapes
// by the thousand on one spot), whose spacing says nothing of the area's.
constexpr double kSpacingFloor = 0.5;

// Half-edge h = 3t + i runs from corner i of triangle t to corner i + 1;
// twin[h] is the half-edge the other way (the mesh is closed and oriented).
std::vector<uint32_t> twins(const TriangleMesh& m) {
  const size_t n = m.triangles.size();
  std::unordered_map<uint64_t, uint32_t> from;
  from.reserve(n);
  const auto key = [](uint64_t a, uint64_t b) { return a << 32 | b; };
  for (size_t h = 0; h < n; ++h) from.emplace(key(m.triangles[h], m.triangles[h - h % 3 + (h % 3 + 1) % 3]), uint32_t(h));
  std::vector<uint32_t> twin(n, UINT32_MAX);
  for (size_t h = 0; h < n; ++h) {
    const auto it = from.find(key(m.triangles[h - h % 3 + (h % 3 + 1) % 3], m.triangles[h]));
    if (it != from.end()) twin[h] = it->second;
  }
  return twin;
}

uint32_t next(uint32_t h) { return h - h % 3 + (h % 3 + 1) % 3; }

// The genus of the triangles t with keep[t], each vertex split into its
// fans of kept triangles (a bow tie is two vertices), every boundary loop
// counted as a hole: sum over components of (2 - euler - loops) / 2.
int64_t kept_genus(const std::vector<uint32_t>& twin, const std::vector<uint8_t>& keep) {
  const uint32_t n = static_cast<uint32_t>(twin.size());
  const auto kept = [&](uint32_t h) { return h != UINT32_MAX && keep[h / 3]; };
  Sets parts(n / 3), fans(n);
  int64_t faces = 0, edges = 0;
  for (uint32_t h = 0; h < n; ++h) {
    if (!kept(h)) continue;
    faces += h % 3 == 0;
    const uint32_t g = twin[h];
    if (!kept(g)) {
      ++edges;
      continue;
    }
    edges += h < g;
    parts.join(h / 3, g / 3);
    fans.join(h, next(g));  // the corner at h's start, in both triangles
    fans.join(next(h), g);  // at its end
  }
  int64_t vertices = 0, components = 0;
  for (uint32_t h = 0; h < n; ++h)
    if (kept(h)) vertices += fans.find(h) == h, components += h % 3 == 0 && parts.find(h / 3) == h / 3;
  // A fan with a boundary has one boundary half-edge leaving its corner:
  // a loop goes from each boundary half-edge to the one leaving its end.
  std::vector<uint32_t> out(n, UINT32_MAX);
  for (uint32_t h = 0; h < n; ++h)
    if (kept(h) && !kept(twin[h])) out[fans.find(h)] = h;
  std::vector<uint8_t> seen(n, 0);
  int64_t loops = 0;
  for (uint32_t h = 0; h < n; ++h) {
    if (!kept(h) || kept(twin[h]) || seen[h]) continue;
    ++loops;
    for (uint32_t x = h; x != UINT32_MAX && !seen[x]; x = out[fans.find(next(x))]) seen[x] = 1;
  }
  return (2 * components - (vertices - edges + faces) - loops) / 2;
}

}  // namespace

std::vector<float> bare_ratios(const TriangleMesh& m, const PointIndex& index, const PointIndex* own) {
  const PointCloud& pc = index.points();
  std::vector<float> nn(pc.size(), -1.0f);  // each point's nearest-neighbour distance, as needed
  const auto spacing_of = [&](uint32_t p) {
    if (nn[p] < 0) {
      uint32_t id[kNeighbour + 1];
      float d2[kNeighbour + 1];
      nn[p] = index.nearest_k(&pc.xyz[3 * size_t(p)], kNeighbour + 1, id, d2) == kNeighbour + 1 ? std::sqrt(d2[kNeighbour]) : 0.0f;
    }
    return nn[p];
  };
  const float floor = static_cast<float>(kSpacingFloor * point_spacing(index, kNeighbour, 0.5));
  std::vector<float> ratio(m.vertex_count(), 0.0f);
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    uint32_t id[kLocalPoints];
    float d2[kLocalPoints];
    const size_t k = index.nearest_k(&m.positions[3 * v], kLocalPoints, id, d2);
    if (k == 0) continue;
    float s[kLocalPoints];
    for (size_t i = 0; i < k; ++i) s[i] = std::max(floor, spacing_of(id[i]));
    std::nth_element(s, s + k / 2, s + k);
    float near = std::sqrt(d2[0]);
    if (own && own->points().size() > 0) {
      const uint32_t o = own->nearest(&m.positions[3 * v]);
      float o2 = 0;
      for (int a = 0; a < 3; ++a) o2 += std::pow(m.positions[3 * v + a] - own->points().xyz[3 * size_t{o} + a], 2.0f);
      near = std::min(near, std::sqrt(o2));
    }
    ratio[v] = s[k / 2] > 0 ? near / s[k / 2] : 0.0f;
  }
  return ratio;
}

std::vector<uint32_t> bare_handles_at(const TriangleMesh& m, const std::vector<float>& ratios, const std::vector<float>& reaches) {
  std::vector<uint32_t> out(reaches.size(), 0);
  const size_t f = m.triangle_count();
  if (f == 0 || ratios.size() != m.vertex_count()) return out;
  const std::vector<uint32_t> twin = twins(m);
  if (std::count(twin.begin(), twin.end(), UINT32_MAX) > 0) return out;
  const int64_t genus = kept_genus(twin, std::vector<uint8_t>(f, 1));
  std::vector<uint8_t> keep(f);
  for (size_t r = 0; r < reaches.size(); ++r) {
    for (size_t t = 0; t < f; ++t) {
      keep[t] = 1;
      for (int c = 0; c < 3; ++c) keep[t] &= ratios[m.triangles[3 * t + c]] <= reaches[r];
    }
    out[r] = static_cast<uint32_t>(std::max<int64_t>(0, genus - kept_genus(twin, keep)));
  }
  return out;
}

uint32_t bare_handles(const TriangleMesh& m, const std::vector<float>& ratios, float reach,
                      std::vector<uint32_t>* bare_vertices) {
  const size_t f = m.triangle_count();
  if (f == 0 || ratios.size() != m.vertex_count()) return 0;
  const std::vector<uint32_t> twin = twins(m);
  if (std::count(twin.begin(), twin.end(), UINT32_MAX) > 0) return 0;  // not closed: no handle count to compare
  std::vector<uint8_t> keep(f, 1), all(f, 1);
  const auto bare = [&](size_t t) {
    for (int c = 0; c < 3; ++c)
      if (ratios[m.triangles[3 * t + c]] > reach) return true;
    return false;
  };
  for (size_t t = 0; t < f; ++t) keep[t] = !bare(t);
  const int64_t lost = kept_genus(twin, all) - kept_genus(twin, keep);
  if (lost <= 0) return 0;
  if (bare_vertices) {
    // Each bare region on its own: the ones whose removal alone loses a
    // handle are named (a region may carry several; a handle through two
    // regions at once names neither, and the count still stands).
    Sets regions(static_cast<uint32_t>(f));
    for (uint32_t h = 0; h < 3 * f; ++h)
      if (!keep[h / 3] && !keep[twin[h] / 3]) regions.join(h / 3, twin[h] / 3);
    for (uint32_t t = 0; t < f; ++t) {
      if (keep[t] || regions.find(t) != t) continue;
      std::vector<uint8_t> one(f, 1);
      for (uint32_t u = 0; u < f; ++u) one[u] = keep[u] || regions.find(u) != t;
      if (kept_genus(twin, one) < kept_genus(twin, all)) bare_vertices->push_back(m.triangles[3 * t]);
    }
  }
  return static_cast<uint32_t>(lost);
}

}  // namespace dbss
