#include "dbss/encoder/outliers.h"

#include <algorithm>
#include <cmath>
#include <array>
#include <future>
#include <system_error>
#include <numeric>
#include <unordered_map>

#include "dbss/encoder/point_distances.h"

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
  // Cells a radius across on the diagonal: points sharing one are linked
  // outright, and only cells up to two apart can hold linked points.  A
  // radius search per point instead costs some hundred neighbours each on
  // a dense scan (16 s for a million points).
  const double cell = radius / std::sqrt(3.0);
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], double{pc.xyz[3 * i + a]}), hi[a] = std::max(hi[a], double{pc.xyz[3 * i + a]});
  bool fits = cell > 0;
  for (int a = 0; a < 3 && fits; ++a) fits = (hi[a] - lo[a]) / cell < double(1 << 20);
  if (!fits) {
    std::vector<uint32_t> near;
    for (size_t i = 0; i < n; ++i) {
      index.within(&pc.xyz[3 * i], static_cast<float>(radius), near);
      for (uint32_t j : near) sets.join(static_cast<uint32_t>(i), j);
    }
  } else {
    const auto key_of = [&](int64_t x, int64_t y, int64_t z) { return uint64_t(x) << 42 | uint64_t(y) << 21 | uint64_t(z); };
    std::vector<std::pair<uint64_t, uint32_t>> order(n);
    for (size_t i = 0; i < n; ++i) {
      int64_t c[3];
      for (int a = 0; a < 3; ++a) c[a] = static_cast<int64_t>((pc.xyz[3 * i + a] - lo[a]) / cell) + 2;
      order[i] = {key_of(c[0], c[1], c[2]), static_cast<uint32_t>(i)};
    }
    std::sort(order.begin(), order.end());
    std::unordered_map<uint64_t, std::pair<size_t, size_t>> cells;  // key -> [begin, end) in `order`
    for (size_t b = 0; b < n;) {
      size_t e = b + 1;
      while (e < n && order[e].first == order[b].first) ++e;
      cells.emplace(order[b].first, std::make_pair(b, e));
      for (size_t k = b + 1; k < e; ++k) sets.join(order[b].second, order[k].second);
      b = e;
    }
    const double r2 = radius * radius;
    const auto close = [&](uint32_t p, uint32_t q) {
      double d2 = 0;
      for (int a = 0; a < 3; ++a) d2 += std::pow(double{pc.xyz[3 * p + a]} - pc.xyz[3 * q + a], 2);
      return d2 <= r2;
    };
    for (const auto& [key, range] : cells) {
      const int64_t x = int64_t(key >> 42), y = int64_t(key >> 21 & 0x1FFFFF), z = int64_t(key & 0x1FFFFF);
      for (int dz = -2; dz <= 2; ++dz)
        for (int dy = -2; dy <= 2; ++dy)
          for (int dx = -2; dx <= 2; ++dx) {
            // Each pair of cells once.
            if (dz < 0 || (dz == 0 && (dy < 0 || (dy == 0 && dx <= 0)))) continue;
            const auto other = cells.find(key_of(x + dx, y + dy, z + dz));
            if (other == cells.end()) continue;
            const uint32_t a0 = order[range.first].second, b0 = order[other->second.first].second;
            if (sets.find(a0) == sets.find(b0)) continue;
            bool linked = false;
            for (size_t i = range.first; i < range.second && !linked; ++i)
              for (size_t j = other->second.first; j < other->second.second && !linked; ++j)
                linked = close(order[i].second, order[j].second);
            if (linked) sets.join(a0, b0);
          }
    }
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

  // Exact duplicates (a mesh's vertices repeated per face) carry nothing
  // and make every spacing figure zero: merged first, then the rest runs
  // on the distinct points.
  {
    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    const auto at = [&](uint32_t i) { return std::array<float, 3>{pc.xyz[3 * i], pc.xyz[3 * i + 1], pc.xyz[3 * i + 2]}; };
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return at(a) != at(b) ? at(a) < at(b) : a < b; });
    std::vector<uint8_t> first(n, 1);
    size_t duplicates = 0;
    for (size_t j = 1; j < n; ++j)
      if (at(order[j]) == at(order[j - 1])) first[order[j]] = 0, ++duplicates;
    if (duplicates > 0) {
      const PointCloud distinct = subset(pc, first);
      const PointIndex distinct_index(distinct);
      OutlierStats inner;
      PointCloud out = remove_outliers(distinct_index, o, &inner);
      inner.points_in = n;
      inner.duplicates = duplicates;
      if (stats) *stats = inner;
      return out;
    }
  }

  // Mean distance to the k nearest other points, for every point.
  std::vector<double> reach(n);
  // Distance to the nearest other point.
  std::vector<double> gap(n);
  // Flat k-per-point neighbour lists (UINT32_MAX where fewer were found).
  std::vector<uint32_t> neighbours(n * k, UINT32_MAX);
  // Both passes are per point and independent: split over the threads
  // (each writes only its own points, so the result is the same on any
  // number).
  const auto in_parallel = [&](const auto& body) {
    const unsigned threads = std::max(1u, std::min<unsigned>(o.threads, static_cast<unsigned>(n / 10000 + 1)));
    std::vector<std::future<void>> helpers;
    for (unsigned t = 1; t < threads; ++t) {
      try {
        helpers.push_back(std::async(std::launch::async, body, n * t / threads, n * (t + 1) / threads));
      } catch (const std::system_error&) {
        body(n * t / threads, n * (t + 1) / threads);  // no thread to be had: here, then
      }
    }
    body(size_t{0}, n / threads);
    for (auto& h : helpers) h.get();
  };
  in_parallel([&](size_t from, size_t to) {
    std::vector<uint32_t> idx(k + 1);
    std::vector<float> d2(k + 1);
    for (size_t i = from; i < to; ++i) {
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
      gap[i] = got > 1 ? std::sqrt(double{d2[1]}) : 0;
    }
  });
  // Each point's distance to the least-squares plane of its neighbours
  // (-1 where too few neighbours were found to fit one).
  std::vector<double> off(n, -1.0), spread(n, 0.0);
  in_parallel([&](size_t from, size_t to) {
    uint32_t ids[64];
    for (size_t i = from; i < to; ++i) {
      size_t m = 0;
      for (size_t j = i * k; j < (i + 1) * k && m < 64; ++j)
        if (neighbours[j] != UINT32_MAX) ids[m++] = neighbours[j];
      if (m < 5) continue;
      PointPlane plane = fit_plane(pc, ids, m);
      const PointPlane first = plane;
      // Once more without the neighbours far off the first plane: a second
      // stray among the neighbours tilts a least-squares plane towards it.
      const auto off_plane = [&](uint32_t q) {
        double d = 0;
        for (int a = 0; a < 3; ++a) d += (pc.xyz[3 * q + a] - plane.point[a]) * plane.normal[a];
        return std::abs(d);
      };
      double residual[64];
      for (size_t j = 0; j < m; ++j) residual[j] = off_plane(ids[j]);
      std::vector<double> sorted(residual, residual + m);
      const double cut = 3.0 * median(sorted);
      size_t inliers = 0;
      for (size_t j = 0; j < m; ++j)
        if (residual[j] <= cut) ids[inliers++] = ids[j];
      if (inliers >= 5 && inliers < m) plane = fit_plane(pc, ids, inliers);
      // Neighbours along a line (a scan line, points piled on an edge)
      // leave the plane's tilt about that line to chance: no test then.
      if (!(plane.variance[1] > 0.05 * plane.variance[2]) || !(first.variance[1] > 0.05 * first.variance[2])) continue;
      // How flat the neighbourhood is: the neighbours' median distance to
      // the plane.  Across a thin wall, round a plate's rim or along a
      // crease it is a good part of the spacing, and standing off the plane
      // says nothing there.
      sorted.clear();
      for (size_t j = 0; j < (inliers >= 5 ? inliers : m); ++j) sorted.push_back(off_plane(ids[j]));
      spread[i] = median(sorted);
      double d = 0;
      for (int a = 0; a < 3; ++a) d += (pc.xyz[3 * i + a] - plane.point[a]) * plane.normal[a];
      off[i] = std::abs(d);
    }
  });
  // Floors for the neighbourhood figures, from the whole cloud: where a
  // sampler or a scanner piled points onto a line or a spot, the figures
  // of a point's neighbours fall to near zero and every ordinary point
  // beside the pile would look far off.
  const double reach_floor = 0.5 * median(reach);
  const double gap_floor = 0.5 * median(gap);
  std::vector<uint8_t> keep(n, 1);
  in_parallel([&](size_t from, size_t to) {
    std::vector<double> around, around_off, around_gap;
    for (size_t i = from; i < to; ++i) {
      around.clear();
      around_off.clear();
      around_gap.clear();
      for (size_t j = i * k; j < (i + 1) * k; ++j) {
        if (neighbours[j] == UINT32_MAX) continue;
        around.push_back(reach[neighbours[j]]);
        around_gap.push_back(gap[neighbours[j]]);
        if (off[neighbours[j]] >= 0) around_off.push_back(off[neighbours[j]]);
      }
      const double local = std::max(median(around), reach_floor);
      if (!(local > 0)) continue;
      bool isolated = reach[i] > o.isolation * local;
      // Near the surface a stray point still has surface points for
      // neighbours, at a spacing or two: it stands off their plane, where a
      // surface point (even at a crease or on a thin wall) lies close to
      // it.  "Off" is measured against the neighbourhood twice: in spacings
      // (`local`), and against how far the neighbours themselves stand off
      // their own planes, so that on a noisy scan the noise's own tails are
      // not taken for strays.  A point on a crease stands off the one plane
      // of both sides too, but it is as close to its nearest point as the
      // surface points are to theirs; a stray is at least its height away.
      // Among points piled far denser than the cloud's usual spacing (a
      // sampler's or a scanner's line along an edge) the plane and the gaps
      // say nothing: no test there.
      const bool piled = median(around_gap) < 0.6 * gap_floor;
      if (!isolated && !piled && off[i] >= 0 && off[i] > o.off_plane * local && off[i] > o.off_noise * median(around_off) &&
          off[i] > o.off_noise * spread[i]) {
        // The nearest neighbour nearer the plane: a second stray beside
        // this one does not count.
        double lower_gap = 0;
        for (size_t j = i * k; j < (i + 1) * k && lower_gap == 0; ++j) {
          const uint32_t q = neighbours[j];
          if (q == UINT32_MAX || !(off[q] >= 0 && off[q] < 0.5 * off[i])) continue;
          double d2 = 0;
          for (int a = 0; a < 3; ++a) d2 += std::pow(double{pc.xyz[3 * i + a]} - pc.xyz[3 * q + a], 2);
          lower_gap = std::sqrt(d2);
        }
        isolated = lower_gap == 0 || lower_gap > o.off_gap * std::max(median(around_gap), gap_floor);
      }
      if (isolated) keep[i] = 0;
    }
  });
  s.isolated = static_cast<size_t>(std::count(keep.begin(), keep.end(), 0));

  // Clusters among the points left.
  PointCloud rest = subset(pc, keep);
  if (rest.size() > k) {
    const PointIndex rest_index(rest);
    uint32_t count = 0;
    const std::vector<uint32_t> cluster = point_clusters(rest_index, cluster_radius(rest_index, o), &count);
    std::vector<size_t> size(count, 0);
    for (uint32_t c : cluster) ++size[c];
    s.clusters = count;
    s.clustered = true;
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
    s.clustered = false;
    if (stats) *stats = s;
    return pc;
  }
  if (stats) *stats = s;
  return subset(pc, keep);
}

}  // namespace dbss
