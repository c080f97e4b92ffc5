#include "dbss/encoder/open_surface.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>
#include <unordered_map>

#include "dbss/encoder/hole_bridge.h"
#include "dbss/encoder/mesh_adjacency.h"
#include "dbss/encoder/point_distances.h"

namespace dbss {

namespace {

uint64_t key(uint32_t a, uint32_t b) { return uint64_t{a} << 32 | b; }

// For every alive triangle's edge k (from corner k to k+1), the alive
// triangle across it, or UINT32_MAX on a boundary.
std::vector<uint32_t> across(const TriangleMesh& m, const std::vector<uint8_t>& alive) {
  const size_t nt = m.triangle_count();
  std::unordered_map<uint64_t, uint32_t> half;
  half.reserve(3 * nt);
  for (uint32_t t = 0; t < nt; ++t)
    if (alive[t])
      for (int k = 0; k < 3; ++k) half[key(m.triangles[3 * t + k], m.triangles[3 * t + (k + 1) % 3])] = t;
  std::vector<uint32_t> out(3 * nt, UINT32_MAX);
  for (uint32_t t = 0; t < nt; ++t)
    if (alive[t])
      for (int k = 0; k < 3; ++k)
        if (auto it = half.find(key(m.triangles[3 * t + (k + 1) % 3], m.triangles[3 * t + k])); it != half.end())
          out[3 * t + k] = it->second;
  return out;
}

// Connected groups of triangles with the same `label` (edge-adjacent);
// returns a group id per triangle and each group's size.
std::vector<uint32_t> groups(const std::vector<uint32_t>& adj, const std::vector<uint8_t>& label,
                             std::vector<size_t>& sizes) {
  const size_t nt = label.size();
  std::vector<uint32_t> id(nt, UINT32_MAX);
  sizes.clear();
  std::vector<uint32_t> stack;
  for (uint32_t s = 0; s < nt; ++s) {
    if (id[s] != UINT32_MAX) continue;
    const uint32_t g = static_cast<uint32_t>(sizes.size());
    sizes.push_back(0);
    id[s] = g;
    stack.push_back(s);
    while (!stack.empty()) {
      const uint32_t t = stack.back();
      stack.pop_back();
      ++sizes[g];
      for (int k = 0; k < 3; ++k) {
        const uint32_t u = adj[3 * t + k];
        if (u != UINT32_MAX && id[u] == UINT32_MAX && label[u] == label[t]) {
          id[u] = g;
          stack.push_back(u);
        }
      }
    }
  }
  return id;
}

std::array<double, 3> face_normal(const TriangleMesh& m, uint32_t t) {
  const float* a = &m.positions[3 * m.triangles[3 * t]];
  const float* b = &m.positions[3 * m.triangles[3 * t + 1]];
  const float* c = &m.positions[3 * m.triangles[3 * t + 2]];
  const double u[3] = {double{b[0]} - a[0], double{b[1]} - a[1], double{b[2]} - a[2]};
  const double v[3] = {double{c[0]} - a[0], double{c[1]} - a[1], double{c[2]} - a[2]};
  std::array<double, 3> n = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (l > 0)
    for (double& x : n) x /= l;
  return n;
}

// Keeps the alive triangles only, renumbering vertices in first-use order.
void compact(TriangleMesh& m, const std::vector<uint8_t>& alive) {
  TriangleMesh out;
  std::vector<uint32_t> id(m.vertex_count(), UINT32_MAX);
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    if (!alive[t]) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = m.triangles[3 * t + k];
      if (id[v] == UINT32_MAX) {
        id[v] = static_cast<uint32_t>(out.vertex_count());
        out.positions.insert(out.positions.end(), &m.positions[3 * v], &m.positions[3 * v + 3]);
      }
      out.triangles.push_back(id[v]);
    }
  }
  m = std::move(out);
}

// One pass of clean_sheet's rules on `alive`; returns triangles dropped.
size_t clean_pass(const TriangleMesh& m, std::vector<uint8_t>& alive) {
  size_t dropped = 0;
  const std::vector<uint32_t> adj = across(m, alive);
  // Ears and slivers hanging by one edge (or none): they make the rim
  // ragged and pin QEM.
  for (uint32_t t = 0; t < m.triangle_count(); ++t) {
    if (!alive[t]) continue;
    int open = 0;
    for (int k = 0; k < 3; ++k) open += adj[3 * t + k] == UINT32_MAX;
    if (open >= 2) alive[t] = 0, ++dropped;
  }
  if (dropped) return dropped;
  // Fans: triangles around a vertex joined across the edges at that vertex.
  std::vector<std::vector<uint32_t>> around(m.vertex_count());
  for (uint32_t t = 0; t < m.triangle_count(); ++t)
    if (alive[t])
      for (int k = 0; k < 3; ++k) around[m.triangles[3 * t + k]].push_back(t);
  std::vector<uint32_t> fan;
  for (uint32_t v = 0; v < m.vertex_count(); ++v) {
    const auto& ts = around[v];
    if (ts.size() < 2) continue;
    fan.assign(ts.size(), UINT32_MAX);
    uint32_t fans = 0;
    for (size_t s = 0; s < ts.size(); ++s) {
      if (fan[s] != UINT32_MAX) continue;
      fan[s] = fans;
      std::vector<size_t> stack{s};
      while (!stack.empty()) {
        const uint32_t t = ts[stack.back()];
        stack.pop_back();
        for (int k = 0; k < 3; ++k) {
          // Only the two edges at v link fans.
          const uint32_t a = m.triangles[3 * t + k], b = m.triangles[3 * t + (k + 1) % 3];
          if (a != v && b != v) continue;
          const uint32_t u = adj[3 * t + k];
          if (u == UINT32_MAX) continue;
          const size_t j = static_cast<size_t>(std::find(ts.begin(), ts.end(), u) - ts.begin());
          if (j < ts.size() && fan[j] == UINT32_MAX) fan[j] = fans, stack.push_back(j);
        }
      }
      ++fans;
    }
    if (fans < 2) continue;
    std::vector<size_t> size(fans, 0);
    for (uint32_t f : fan) ++size[f];
    const uint32_t best = static_cast<uint32_t>(std::max_element(size.begin(), size.end()) - size.begin());
    for (size_t s = 0; s < ts.size(); ++s)
      if (fan[s] != best && alive[ts[s]]) alive[ts[s]] = 0, ++dropped;
    if (dropped) return dropped;  // adjacency is stale now
  }
  return dropped;
}

size_t clean_alive(const TriangleMesh& m, std::vector<uint8_t>& alive) {
  size_t total = 0;
  for (int pass = 0; pass < 10000; ++pass) {
    const size_t d = clean_pass(m, alive);
    if (d == 0) break;
    total += d;
  }
  return total;
}

}  // namespace

std::vector<std::array<float, 3>> oriented_normals(const PointIndex& index, size_t k) {
  const PointCloud& pc = index.points();
  const size_t n = pc.size();
  k = std::max<size_t>(k, 4);
  std::vector<std::array<double, 3>> nrm(n);
  std::vector<uint32_t> knn(n * k, UINT32_MAX);
  std::vector<uint32_t> idx(k + 1);
  std::vector<float> d2(k + 1);
  for (size_t i = 0; i < n; ++i) {
    const size_t got = index.nearest_k(&pc.xyz[3 * i], k + 1, idx.data(), d2.data());
    nrm[i] = fit_plane(pc, idx.data(), got).normal;
    size_t w = 0;
    for (size_t j = 0; j < got && w < k; ++j)
      if (idx[j] != i) knn[i * k + w++] = idx[j];
  }
  // Prim's tree over the k-nearest-neighbour graph, from each not yet
  // reached point in turn; a point takes the orientation of the one that
  // reached it.
  struct Edge {
    double cost;
    uint32_t from, to;
    bool operator>(const Edge& o) const { return cost > o.cost || (cost == o.cost && to > o.to); }
  };
  std::vector<uint8_t> reached(n, 0);
  std::vector<uint32_t> tree(n, 0);
  uint32_t trees = 0;
  std::priority_queue<Edge, std::vector<Edge>, std::greater<Edge>> heap;
  const auto dot = [&](uint32_t a, uint32_t b) {
    return nrm[a][0] * nrm[b][0] + nrm[a][1] * nrm[b][1] + nrm[a][2] * nrm[b][2];
  };
  const auto reach = [&](uint32_t v) {
    reached[v] = 1;
    for (size_t j = v * k; j < (v + 1) * k; ++j)
      if (uint32_t w = knn[j]; w != UINT32_MAX && !reached[w]) heap.push({1 - std::abs(dot(v, w)), v, w});
  };
  for (uint32_t s = 0; s < n; ++s) {
    if (reached[s]) continue;
    tree[s] = trees;
    reach(s);
    while (!heap.empty()) {
      const Edge e = heap.top();
      heap.pop();
      if (reached[e.to]) continue;
      if (dot(e.from, e.to) < 0)
        for (double& x : nrm[e.to]) x = -x;
      tree[e.to] = trees;
      reach(e.to);
    }
    ++trees;
  }
  // Each tree as a whole: most normals away from its centroid (outward on a
  // convex cap; a guess elsewhere, either side serves).
  std::vector<std::array<double, 3>> centre(trees, {0, 0, 0});
  std::vector<size_t> count(trees, 0);
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) centre[tree[i]][a] += pc.xyz[3 * i + a];
    ++count[tree[i]];
  }
  std::vector<double> outward(trees, 0);
  for (size_t i = 0; i < n; ++i) {
    const auto& c = centre[tree[i]];
    double s = 0;
    for (int a = 0; a < 3; ++a) s += (pc.xyz[3 * i + a] - c[a] / count[tree[i]]) * nrm[i][a];
    outward[tree[i]] += s;
  }
  std::vector<std::array<float, 3>> out(n);
  for (size_t i = 0; i < n; ++i) {
    const double sign = outward[tree[i]] < 0 ? -1.0 : 1.0;
    for (int a = 0; a < 3; ++a) out[i][a] = static_cast<float>(sign * nrm[i][a]);
  }
  return out;
}

std::vector<uint8_t> thin_under(const TriangleMesh& shell, const CellGrid& g, int cells) {
  std::vector<uint8_t> thin(shell.triangle_count(), 0);
  for (uint32_t t = 0; t < shell.triangle_count(); ++t) {
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) c[a] += shell.positions[3 * shell.triangles[3 * t + k] + a] / 3.0;
    const auto n = face_normal(shell, t);
    // From the middle of the first cell under the face, a cell per step.
    for (int step = 0; step < cells; ++step) {
      int ijk[3];
      bool outside = false;
      for (int a = 0; a < 3; ++a) {
        ijk[a] = static_cast<int>(std::floor((c[a] - (0.5 + step) * g.cell * n[a] - g.origin[a]) / g.cell));
        outside = outside || ijk[a] < 0 || ijk[a] >= g.n[a];
      }
      const uint8_t st = outside ? uint8_t{CellGrid::kAir} : g.state[g.index(ijk[0], ijk[1], ijk[2])];
      if (st == CellGrid::kInside || st == CellGrid::kFilled) break;
      if (st == CellGrid::kAir && step > 0) {
        thin[t] = 1;
        break;
      }
    }
  }
  return thin;
}

SheetCut cut_to_sheet(const TriangleMesh& shell, const PointIndex& index, const std::vector<std::array<float, 3>>& normals,
                      const std::vector<uint8_t>* thin) {
  const PointCloud& pc = index.points();
  const size_t nt = shell.triangle_count();
  double edge = 0;
  for (size_t t = 0; t < nt; ++t) {
    const float* a = &shell.positions[3 * shell.triangles[3 * t]];
    const float* b = &shell.positions[3 * shell.triangles[3 * t + 1]];
    edge += std::sqrt(std::pow(double{a[0]} - b[0], 2) + std::pow(double{a[1]} - b[1], 2) + std::pow(double{a[2]} - b[2], 2));
  }
  edge /= std::max<size_t>(1, nt);
  std::vector<uint8_t> keep(nt, 0), behind(nt, 0);
  for (uint32_t t = 0; t < nt; ++t) {
    float c[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) c[a] += shell.positions[3 * shell.triangles[3 * t + k] + a] / 3.0f;
    const uint32_t p = index.nearest(c);
    const auto fn = face_normal(shell, t);
    keep[t] = fn[0] * normals[p][0] + fn[1] * normals[p][1] + fn[2] * normals[p][2] > 0;
    // Against the local mid-surface (the centroid of the nearest points),
    // not the nearest point: a noisy scan is a layer, and the shell lies
    // outside all of it.
    uint32_t near[12];
    float d2[12];
    const size_t got = index.nearest_k(c, 12, near, d2);
    double mid[3] = {0, 0, 0};
    for (size_t j = 0; j < got; ++j)
      for (int a = 0; a < 3; ++a) mid[a] += pc.xyz[3 * near[j] + a] / static_cast<double>(got);
    double off = 0;
    for (int a = 0; a < 3; ++a) off += (c[a] - mid[a]) * normals[p][a];
    behind[t] = off < -0.25 * edge;
  }
  // Islands: a noisy normal flips a few triangles to the wrong side.
  const std::vector<uint8_t> all(nt, 1);
  const std::vector<uint32_t> adj = across(shell, all);
  std::vector<size_t> sizes;
  std::vector<uint32_t> group = groups(adj, keep, sizes);
  const size_t kept = static_cast<size_t>(std::count(keep.begin(), keep.end(), 1));
  const double small = 0.01 * static_cast<double>(kept);
  std::vector<uint8_t> flip(sizes.size(), 0);
  for (size_t g = 0; g < sizes.size(); ++g) flip[g] = static_cast<double>(sizes[g]) < small;
  // A small dropped island (kept triangles all round it, or it would join
  // a larger dropped group) comes back only if what surrounds it stays: a
  // stray point's own little closed shell has a small kept half and a small
  // dropped half, and goes whole.
  std::vector<uint8_t> back(sizes.size(), 1);
  for (uint32_t t = 0; t < nt; ++t)
    if (!keep[t] && flip[group[t]])
      for (int k = 0; k < 3; ++k)
        if (const uint32_t u = adj[3 * t + k]; keep[u] && flip[group[u]]) back[group[t]] = 0;
  for (size_t g = 0; g < sizes.size(); ++g) flip[g] = flip[g] && back[g];
  for (uint32_t t = 0; t < nt; ++t)
    if (flip[group[t]]) keep[t] = !keep[t];
  clean_alive(shell, keep);
  SheetCut out;
  out.sheet = shell;
  compact(out.sheet, keep);
  out.removed = nt - out.sheet.triangle_count();
  for (size_t t = 0; t < nt; ++t) out.behind += !keep[t] && behind[t] && (!thin || (*thin)[t]);
  return out;
}

size_t trim_unsupported(TriangleMesh& m, const PointIndex& index, double reach) {
  const PointCloud& pc = index.points();
  const double r2 = reach * reach;
  const auto far = [&](const float* q) {
    const uint32_t p = index.nearest(q);
    double d2 = 0;
    for (int a = 0; a < 3; ++a) d2 += (q[a] - double{pc.xyz[3 * p + a]}) * (q[a] - double{pc.xyz[3 * p + a]});
    return d2 > r2;
  };
  std::vector<uint8_t> alive(m.triangle_count(), 1);
  size_t removed = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    float c[3] = {0, 0, 0};
    bool all_far = true;
    for (int k = 0; k < 3; ++k) {
      const float* v = &m.positions[3 * m.triangles[3 * t + k]];
      all_far = all_far && far(v);
      for (int a = 0; a < 3; ++a) c[a] += v[a] / 3.0f;
    }
    if (all_far && far(c)) alive[t] = 0, ++removed;
  }
  removed += clean_alive(m, alive);
  compact(m, alive);
  return removed;
}

std::vector<std::vector<uint32_t>> boundary_loops(const TriangleMesh& m) {
  const std::vector<uint8_t> all(m.triangle_count(), 1);
  const std::vector<uint32_t> adj = across(m, all);
  // On a manifold each boundary vertex starts exactly one boundary half-edge.
  std::unordered_map<uint32_t, uint32_t> next;
  for (size_t t = 0; t < m.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k)
      if (adj[3 * t + k] == UINT32_MAX) next[m.triangles[3 * t + k]] = m.triangles[3 * t + (k + 1) % 3];
  std::vector<uint32_t> starts;
  for (const auto& [a, b] : next) starts.push_back(a);
  std::sort(starts.begin(), starts.end());  // a stable order, whatever the map's
  std::vector<std::vector<uint32_t>> loops;
  std::unordered_map<uint32_t, uint8_t> used;
  for (uint32_t s : starts) {
    if (used[s]) continue;
    std::vector<uint32_t> loop;
    for (uint32_t v = s; !used[v]; v = next[v]) {
      used[v] = 1;
      loop.push_back(v);
      if (!next.count(next[v])) break;
    }
    if (loop.size() >= 3) loops.push_back(std::move(loop));
  }
  return loops;
}

double triangle_area(const TriangleMesh& m, size_t t) {
  const float* a = &m.positions[3 * m.triangles[3 * t]];
  const float* b = &m.positions[3 * m.triangles[3 * t + 1]];
  const float* c = &m.positions[3 * m.triangles[3 * t + 2]];
  const double u[3] = {double{b[0]} - a[0], double{b[1]} - a[1], double{b[2]} - a[2]};
  const double v[3] = {double{c[0]} - a[0], double{c[1]} - a[1], double{c[2]} - a[2]};
  const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
  return 0.5 * std::sqrt(x * x + y * y + z * z);
}

double loop_perimeter(const TriangleMesh& m, const std::vector<uint32_t>& loop) {
  const size_t n = loop.size();
  double perimeter = 0;
  for (size_t i = 0; i < n; ++i) {
    double d2 = 0;
    for (int a = 0; a < 3; ++a) d2 += std::pow(double{m.positions[3 * loop[i] + a]} - m.positions[3 * loop[(i + 1) % n] + a], 2);
    perimeter += std::sqrt(d2);
  }
  return perimeter;
}

double mesh_area(const TriangleMesh& m) {
  double area = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t) area += triangle_area(m, t);
  return area;
}

HoleFill fill_holes(TriangleMesh& m, double edge, double max_perimeter, bool bridge) {
  HoleFill out;
  const size_t triangles_before = m.triangle_count();
  std::vector<std::vector<uint32_t>> loops;
  for (std::vector<uint32_t>& loop : boundary_loops(m))
    if (loop_perimeter(m, loop) < max_perimeter) loops.push_back(std::move(loop));
  // Two ends of a tube the scan cut through are joined, not capped (a cap
  // on each would cut the handle off); their vertices are placed on the
  // tube already and skip the membrane and fairing below.
  std::vector<uint32_t> tube_vertices;
  if (bridge) {
    const size_t before = loops.size();
    const size_t first = m.triangles.size();
    out.bridges = bridge_facing_loops(m, loops, edge, tube_vertices, &out.doubtful_pairs);
    out.loops += before - loops.size();
    for (size_t i = first; i < m.triangles.size(); ++i)
      for (int a = 0; a < 3; ++a) out.bridge_triangles.push_back(m.positions[3 * size_t{m.triangles[i]} + a]);
  }
  for (const std::vector<uint32_t>& loop : loops) {
    const size_t n = loop.size();
    double c[3] = {0, 0, 0}, radius = 0;
    for (uint32_t v : loop)
      for (int a = 0; a < 3; ++a) c[a] += m.positions[3 * v + a] / static_cast<double>(n);
    for (uint32_t v : loop) {
      double d2 = 0;
      for (int a = 0; a < 3; ++a) d2 += std::pow(m.positions[3 * v + a] - c[a], 2);
      radius += std::sqrt(d2) / static_cast<double>(n);
    }
    // Rings about two edges apart keep the patch's triangles from being
    // needles near the loop without making the centre a dense fan.
    const int rings = edge > 0 ? std::clamp(static_cast<int>(radius / (2 * edge)), 0, 16) : 0;
    std::vector<uint32_t> outer = loop;
    const auto add_vertex = [&](const double p[3]) {
      const uint32_t id = static_cast<uint32_t>(m.vertex_count());
      for (int a = 0; a < 3; ++a) m.positions.push_back(static_cast<float>(p[a]));
      out.added_vertices.push_back(id);
      return id;
    };
    for (int r = 1; r <= rings; ++r) {
      std::vector<uint32_t> inner(n);
      const double f = 1.0 - static_cast<double>(r) / (rings + 1);
      for (size_t i = 0; i < n; ++i) {
        double p[3];
        for (int a = 0; a < 3; ++a) p[a] = c[a] + (m.positions[3 * loop[i] + a] - c[a]) * f;
        inner[i] = add_vertex(p);
      }
      // The boundary half-edge a->b has the sheet on its left; the patch
      // takes b->a.
      for (size_t i = 0; i < n; ++i) {
        const uint32_t a = outer[i], b = outer[(i + 1) % n], ia = inner[i], ib = inner[(i + 1) % n];
        m.triangles.insert(m.triangles.end(), {b, a, ia, b, ia, ib});
      }
      outer = std::move(inner);
    }
    // The innermost ring is closed by a zig-zag strip rather than a fan: a
    // fan's centre would take the loop's whole length as valence (the
    // decoder allows 64).  Each triangle takes the ring's edges reversed.
    size_t l = 0, r = n - 1;
    while (r - l > 1) {
      m.triangles.insert(m.triangles.end(), {outer[l + 1], outer[l], outer[r]});
      ++l;
      if (r - l > 1) {
        m.triangles.insert(m.triangles.end(), {outer[l], outer[r], outer[r - 1]});
        --r;
      }
    }
    ++out.loops;
  }
  out.triangles = m.triangle_count() - triangles_before;
  // The tubes are placed on curves that continue the surface already
  // (hole_bridge.cpp); fairing would pull their bend straight.
  const std::vector<uint32_t> disk_vertices = out.added_vertices;
  out.added_vertices.insert(out.added_vertices.end(), tube_vertices.begin(), tube_vertices.end());
  if (disk_vertices.empty()) {
    for (size_t t = triangles_before; t < m.triangle_count(); ++t) out.area += triangle_area(m, t);
    return out;
  }
  // Membrane: the new vertices of the disks relax to their neighbours' mean.
  const Adjacency adj = vertex_adjacency(m);
  for (int it = 0; it < 60; ++it)
    for (uint32_t v : disk_vertices) {
      double mean[3] = {0, 0, 0};
      const uint32_t deg = adj.offset[v + 1] - adj.offset[v];
      for (uint32_t i = adj.offset[v]; i < adj.offset[v + 1]; ++i)
        for (int a = 0; a < 3; ++a) mean[a] += m.positions[3 * adj.index[i] + a];
      for (int a = 0; a < 3; ++a) m.positions[3 * v + a] = static_cast<float>(mean[a] / deg);
    }
  // Fairing: a flat membrane meets a curved scan at a crease, which the
  // butterfly rule overshoots; Gauss-Seidel steps on the umbrella operator
  // applied twice (Kobbelt's discrete fairing) bend the patch so its slope
  // follows the surface around the hole.  The loop and the rest stay put.
  std::vector<uint8_t> in_fill(m.vertex_count(), 0), near_fill(m.vertex_count(), 0);
  for (uint32_t v : disk_vertices) in_fill[v] = near_fill[v] = 1;
  std::vector<uint32_t> ring;
  for (uint32_t v : disk_vertices)
    for (uint32_t i = adj.offset[v]; i < adj.offset[v + 1]; ++i)
      if (!near_fill[adj.index[i]]) near_fill[adj.index[i]] = 1, ring.push_back(adj.index[i]);
  std::vector<double> u(3 * m.vertex_count(), 0);
  const auto umbrella = [&](uint32_t v) {
    const uint32_t deg = adj.offset[v + 1] - adj.offset[v];
    for (int a = 0; a < 3; ++a) {
      double mean = 0;
      for (uint32_t i = adj.offset[v]; i < adj.offset[v + 1]; ++i) mean += m.positions[3 * adj.index[i] + a];
      u[3 * v + a] = mean / deg - m.positions[3 * v + a];
    }
  };
  for (int it = 0; it < 200; ++it) {
    for (uint32_t v : ring) umbrella(v);
    for (uint32_t v : disk_vertices) umbrella(v);
    for (uint32_t v : disk_vertices) {
      const uint32_t deg = adj.offset[v + 1] - adj.offset[v];
      double nu = 0, u2[3] = {0, 0, 0};
      for (uint32_t i = adj.offset[v]; i < adj.offset[v + 1]; ++i) {
        const uint32_t w = adj.index[i];
        nu += 1.0 / (adj.offset[w + 1] - adj.offset[w]);
        for (int a = 0; a < 3; ++a) u2[a] += u[3 * w + a] / deg;
      }
      nu = 1 + nu / deg;
      for (int a = 0; a < 3; ++a) m.positions[3 * v + a] -= static_cast<float>((u2[a] - u[3 * v + a]) / nu);
      umbrella(v);
    }
  }
  for (size_t t = triangles_before; t < m.triangle_count(); ++t) out.area += triangle_area(m, t);
  return out;
}

}  // namespace dbss
