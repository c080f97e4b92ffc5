#include "dbss/encoder/outliers.h"
#include "split_ranges.h"
#include "union_find.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <array>
#include <memory>
#include <numeric>

#include "dbss/encoder/point_distances.h"

namespace dbss {

namespace {

// The median of v, reordering v (which keeps the same values): the
// per-point passes call it on their own scratch buffers, a copy (and an
// allocation) per call avoided.
// Batcher's odd-even merge sort of 16 values as a list of compare-exchanges
// (63 of them): the same steps whatever the values, so no branch to guess.
constexpr auto kNetwork16 = [] {
  std::array<std::array<uint8_t, 2>, 63> pairs{};
  size_t count = 0;
  constexpr int n = 16;
  for (int p = 1; p < n; p *= 2)
    for (int k = p; k >= 1; k /= 2)
      for (int j = k % p; j + k < n; j += 2 * k)
        for (int i = 0; i < k && i + j + k < n; ++i)
          if ((i + j) / (2 * p) == (i + j + k) / (2 * p)) pairs[count++] = {uint8_t(i + j), uint8_t(i + j + k)};
  return pairs;
}();

double median_in_place(std::vector<double>& v) {
  if (v.empty()) return 0;
  const size_t mid = v.size() / 2;
  if (v.size() <= 16) {
    // The per-point lists (16 figures, fewer where some are missing),
    // padded with infinities that sort last: the network is 3-4 times
    // quicker than the insertion sort it replaces (8% of the CPU at 10M
    // points, branches mispredicted), and v[mid] is the same value either
    // way (the figures are distances: no NaN, no -0).
    double a[16];
    std::fill(std::copy(v.begin(), v.end(), a), a + 16, std::numeric_limits<double>::infinity());
    for (const auto& [x, y] : kNetwork16) {
      const double lo = std::min(a[x], a[y]), hi = std::max(a[x], a[y]);
      a[x] = lo, a[y] = hi;
    }
    std::copy(a, a + v.size(), v.begin());
    return v[mid];
  }
  if (v.size() <= 32) {
    // The per-point lists (16 figures): an insertion sort is several
    // times quicker than nth_element there (which took 9 of the 70 s of
    // CPU at 10M points), and v[mid] is the same value either way.
    for (size_t i = 1; i < v.size(); ++i) {
      const double x = v[i];
      size_t j = i;
      for (; j > 0 && x < v[j - 1]; --j) v[j] = v[j - 1];
      v[j] = x;
    }
    return v[mid];
  }
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  return v[mid];
}

double median(std::vector<double> v) { return median_in_place(v); }

// Spreads the low 21 bits of x to every third bit (a Morton code's axis).
uint64_t spread_bits(uint64_t x) {
  x &= 0x1FFFFF;
  x = (x | x << 32) & 0x1F00000000FFFFull;
  x = (x | x << 16) & 0x1F0000FF0000FFull;
  x = (x | x << 8) & 0x100F00F00F00F00Full;
  x = (x | x << 4) & 0x10C30C30C30C30C3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

bool same_point(const PointCloud& pc, size_t a, size_t b) {
  return pc.xyz[3 * a] == pc.xyz[3 * b] && pc.xyz[3 * a + 1] == pc.xyz[3 * b + 1] && pc.xyz[3 * a + 2] == pc.xyz[3 * b + 2];
}

// The points' indices sorted by Morton code of their cell in a 2^21 grid
// over the bounding box, then by position, then by index.
std::vector<uint32_t> morton_order(const PointCloud& pc) {
  const size_t n = pc.size();
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], double{pc.xyz[3 * i + a]}), hi[a] = std::max(hi[a], double{pc.xyz[3 * i + a]});
  double scale[3];
  for (int a = 0; a < 3; ++a) scale[a] = hi[a] > lo[a] ? (double(1 << 21) - 1) / (hi[a] - lo[a]) : 0;
  std::vector<std::pair<uint64_t, uint32_t>> keyed(n);
  for (size_t i = 0; i < n; ++i) {
    uint64_t key = 0;
    for (int a = 0; a < 3; ++a) key |= spread_bits(static_cast<uint64_t>((pc.xyz[3 * i + a] - lo[a]) * scale[a])) << a;
    keyed[i] = {key, static_cast<uint32_t>(i)};
  }
  const auto at = [&](uint32_t i) { return std::array<float, 3>{pc.xyz[3 * i], pc.xyz[3 * i + 1], pc.xyz[3 * i + 2]}; };
  std::sort(keyed.begin(), keyed.end(), [&](const auto& x, const auto& y) {
    if (x.first != y.first) return x.first < y.first;
    const auto px = at(x.second), py = at(y.second);
    return px != py ? px < py : x.second < y.second;
  });
  std::vector<uint32_t> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = keyed[i].second;
  return order;
}

// The least-squares plane of the points `ids` of xyz, as fit_plane finds
// it (the same centroid and covariance, summed in the same order) but with
// Eigen's closed-form solve of the 3x3 covariance (computeDirect: the cubic's
// roots, then cross products) instead of its iterative one, which took 14%
// of the encoder's CPU at 10M points (two fits a point).  The two differ by
// rounding; the tests below use the normal's direction (not its sign) and
// the two larger variances, neither near-degenerate where they decide.
PointPlane neighbour_plane(const std::vector<float>& xyz, const uint32_t* ids, size_t m) {
  PointPlane out;
  double c[3] = {0, 0, 0};
  for (size_t j = 0; j < m; ++j)
    for (int a = 0; a < 3; ++a) c[a] += double{xyz[3 * size_t{ids[j]} + a]};
  for (double& v : c) v /= static_cast<double>(m);
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
  for (size_t j = 0; j < m; ++j) {
    const double dx = double{xyz[3 * size_t{ids[j]}]} - c[0], dy = double{xyz[3 * size_t{ids[j]} + 1]} - c[1],
                 dz = double{xyz[3 * size_t{ids[j]} + 2]} - c[2];
    xx += dx * dx, xy += dx * dy, xz += dx * dz, yy += dy * dy, yz += dy * dz, zz += dz * dz;
  }
  Eigen::Matrix3d cov;
  cov << xx, xy, xz, xy, yy, yz, xz, yz, zz;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(cov);  // eigenvalues ascending, as compute() gives them
  const Eigen::Vector3d n = eig.eigenvectors().col(0);
  out.point = {c[0], c[1], c[2]};
  out.normal = {n[0], n[1], n[2]};
  const Eigen::Vector3d v = eig.eigenvalues() / static_cast<double>(m);
  out.variance = {v[0], v[1], v[2]};
  return out;
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
  // Each point's cluster as any one member of it (a point, or a cell), then
  // numbered below.
  std::vector<uint32_t> group(n);
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
    Sets sets(n);
    std::vector<uint32_t> near;
    for (size_t i = 0; i < n; ++i) {
      index.within(&pc.xyz[3 * i], static_cast<float>(radius), near);
      for (uint32_t j : near) sets.join(static_cast<uint32_t>(i), j);
    }
    for (size_t i = 0; i < n; ++i) group[i] = sets.find(static_cast<uint32_t>(i));
  } else {
    // Cell coordinates 2 and up, under 2^21 - 2: a neighbour's key is the
    // key plus the offset's, with no carry between the fields.
    const auto key_of = [&](int64_t x, int64_t y, int64_t z) { return uint64_t(x) << 42 | uint64_t(y) << 21 | uint64_t(z); };
    std::vector<std::pair<uint64_t, uint32_t>> order(n);
    for (size_t i = 0; i < n; ++i) {
      int64_t c[3];
      for (int a = 0; a < 3; ++a) c[a] = static_cast<int64_t>((pc.xyz[3 * i + a] - lo[a]) / cell) + 2;
      order[i] = {key_of(c[0], c[1], c[2]), static_cast<uint32_t>(i)};
    }
    std::sort(order.begin(), order.end());
    // The union-find runs over the occupied cells (a tenth as many as the
    // points on a dense scan, and their points joined for free), and the
    // points' coordinates are copied in cell order, so the tests between
    // two cells read them side by side: over 10M points in random order,
    // union-find and tests on the points themselves took 16 s, most of it
    // waiting on memory.
    std::vector<uint64_t> keys;
    std::vector<size_t> first;  // each cell's start in `order`, and n
    std::vector<uint32_t> cell_of(n);
    std::vector<float> xyz(3 * n);
    for (size_t b = 0; b < n; ++b) {
      if (b == 0 || order[b].first != order[b - 1].first) keys.push_back(order[b].first), first.push_back(b);
      cell_of[order[b].second] = static_cast<uint32_t>(keys.size() - 1);
      for (int a = 0; a < 3; ++a) xyz[3 * b + a] = pc.xyz[3 * size_t{order[b].second} + a];
    }
    first.push_back(n);
    std::vector<std::pair<uint64_t, uint32_t>>().swap(order);  // 16 bytes a point, no longer needed
    const size_t cells = keys.size();
    Sets sets(cells);
    const double r2 = radius * radius;
    const auto close = [&](size_t p, size_t q) {
      double d2 = 0;
      for (int a = 0; a < 3; ++a) d2 += std::pow(double{xyz[3 * p + a]} - xyz[3 * q + a], 2);
      return d2 <= r2;
    };
    for (int dz = -2; dz <= 2; ++dz)
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          // Each pair of cells once.
          if (dz < 0 || (dz == 0 && (dy < 0 || (dy == 0 && dx <= 0)))) continue;
          // The keys shifted by one offset are still in order: one merge
          // over the sorted keys finds every pair of cells at that offset.
          const uint64_t delta = uint64_t(int64_t{dx} * (int64_t{1} << 42) + int64_t{dy} * (int64_t{1} << 21) + dz);
          size_t other = 0;
          for (size_t c = 0; c < cells; ++c) {
            const uint64_t want = keys[c] + delta;
            while (other < cells && keys[other] < want) ++other;
            if (other == cells) break;
            if (keys[other] != want) continue;
            if (sets.find(static_cast<uint32_t>(c)) == sets.find(static_cast<uint32_t>(other))) continue;
            bool linked = false;
            for (size_t i = first[c]; i < first[c + 1] && !linked; ++i)
              for (size_t j = first[other]; j < first[other + 1] && !linked; ++j) linked = close(i, j);
            if (linked) sets.join(static_cast<uint32_t>(c), static_cast<uint32_t>(other));
          }
        }
    for (size_t i = 0; i < n; ++i) group[i] = sets.find(cell_of[i]);
  }
  // Numbering the groups in order of their first point gives ids in order
  // of first point.
  std::vector<uint32_t> id(n), group_id(n, UINT32_MAX);
  uint32_t c = 0;
  for (size_t i = 0; i < n; ++i) {
    if (group_id[group[i]] == UINT32_MAX) group_id[group[i]] = c++;
    id[i] = group_id[group[i]];
  }
  if (count) *count = c;
  return id;
}

double cluster_radius(const PointIndex& index, const OutlierOptions& o) { return o.link * point_spacing(index, 1, 0.99); }

PointCloud remove_outliers(const PointIndex& index, const OutlierOptions& o, OutlierStats* stats) {
  PointCloud out;
  remove_outliers(index, o, stats, out);
  return out;
}

std::unique_ptr<PointIndex> remove_outliers(const PointIndex& index, const OutlierOptions& o, OutlierStats* stats,
                                            PointCloud& out) {
  const PointCloud& pc = index.points();
  const size_t n = pc.size();
  OutlierStats s;
  s.points_in = n;
  if (stats) *stats = s;
  const uint32_t k = std::max<uint32_t>(1, o.k);
  if (!o.enabled || n <= size_t{k} + 4) {
    out = pc;
    return nullptr;
  }

  // The points in Morton order (the cells of a 2^21 grid over the
  // bounding box, along a Z curve): the per-point passes below visit them
  // in this order, so that consecutive k-d tree searches walk the same
  // nodes and leaves and find them in cache.  On 10M points in random order
  // the searches went from 5.7 s at 1M to 143 s at 10M (cache misses), and
  // the result of each point does not depend on the order it is visited in.
  // Equal points have equal keys: sorted by (key, position, index), exact
  // duplicates sit side by side, the first of each its earliest.
  const std::vector<uint32_t> order = morton_order(pc);
  {
    std::vector<uint8_t> first(n, 1);
    size_t duplicates = 0;
    for (size_t j = 1; j < n; ++j)
      if (same_point(pc, order[j], order[j - 1])) first[order[j]] = 0, ++duplicates;
    // Exact duplicates (a mesh's vertices repeated per face) carry nothing
    // and make every spacing figure zero: merged first, then the rest runs
    // on the distinct points.
    if (duplicates > 0) {
      const PointCloud distinct = subset(pc, first);
      const PointIndex distinct_index(distinct);
      OutlierStats inner;
      std::unique_ptr<PointIndex> kept_index = remove_outliers(distinct_index, o, &inner, out);
      inner.points_in = n;
      inner.duplicates = duplicates;
      if (stats) *stats = inner;
      return kept_index;
    }
  }

  // From here the per-point figures are kept by rank in that order (rank r
  // is point order[r]), the neighbours as ranks and the coordinates copied
  // in the same order: a point's neighbours then lie near it in memory as
  // they do in space.  Read by input index, on 10M points in random order,
  // nearly every neighbour's coordinates and figures missed the cache.
  std::vector<uint32_t> rank_of(n);
  PointCloud ranked;
  ranked.xyz.resize(3 * n);
  for (size_t r = 0; r < n; ++r) {
    rank_of[order[r]] = static_cast<uint32_t>(r);
    for (int a = 0; a < 3; ++a) ranked.xyz[3 * r + a] = pc.xyz[3 * size_t{order[r]} + a];
  }
  const std::vector<float>& xyz = ranked.xyz;
  // Mean distance to the k nearest other points, for every point.
  std::vector<double> reach(n);
  // Distance to the nearest other point.
  std::vector<double> gap(n);
  // Flat k-per-point neighbour lists (UINT32_MAX where fewer were found).
  std::vector<uint32_t> neighbours(n * k, UINT32_MAX);
  // Both passes are per point and independent: split over the threads
  // (each writes only its own points, so the result is the same on any
  // number).
  const auto in_parallel = [&](const auto& body) { detail::split_ranges(n, o.threads, body); };
  in_parallel([&](size_t from, size_t to) {
    std::vector<uint32_t> idx(k + 1);
    std::vector<float> d2(k + 1);
    for (size_t r = from; r < to; ++r) {
      const size_t got = index.nearest_k(&xyz[3 * r], k + 1, idx.data(), d2.data());
      double sum = 0;
      size_t used = 0;
      // The first hit is the point itself (or a duplicate of it): skip one.
      for (size_t j = 1; j < got; ++j) {
        sum += std::sqrt(double{d2[j]});
        ++used;
        neighbours[r * k + j - 1] = rank_of[idx[j]];
      }
      reach[r] = used ? sum / used : 0;
      gap[r] = got > 1 ? std::sqrt(double{d2[1]}) : 0;
    }
  });
  // Each point's distance to the least-squares plane of its neighbours
  // (-1 where too few neighbours were found to fit one).
  std::vector<double> off(n, -1.0), spread(n, 0.0);
  in_parallel([&](size_t from, size_t to) {
    uint32_t ids[64];
    std::vector<double> sorted;
    for (size_t r = from; r < to; ++r) {
      size_t m = 0;
      for (size_t j = r * k; j < (r + 1) * k && m < 64; ++j)
        if (neighbours[j] != UINT32_MAX) ids[m++] = neighbours[j];
      if (m < 5) continue;
      PointPlane plane = neighbour_plane(xyz, ids, m);
      const PointPlane first = plane;
      // Once more without the neighbours far off the first plane: a second
      // stray among the neighbours tilts a least-squares plane towards it.
      const auto off_plane = [&](uint32_t q) {
        double d = 0;
        for (int a = 0; a < 3; ++a) d += (xyz[3 * q + a] - plane.point[a]) * plane.normal[a];
        return std::abs(d);
      };
      double residual[64];
      for (size_t j = 0; j < m; ++j) residual[j] = off_plane(ids[j]);
      sorted.assign(residual, residual + m);
      const double cut = 3.0 * median_in_place(sorted);
      size_t inliers = 0;
      for (size_t j = 0; j < m; ++j)
        if (residual[j] <= cut) ids[inliers++] = ids[j];
      if (inliers >= 5 && inliers < m) plane = neighbour_plane(xyz, ids, inliers);
      // Neighbours along a line (a scan line, points piled on an edge)
      // leave the plane's tilt about that line to chance: no test then.
      if (!(plane.variance[1] > 0.05 * plane.variance[2]) || !(first.variance[1] > 0.05 * first.variance[2])) continue;
      // How flat the neighbourhood is: the neighbours' median distance to
      // the plane.  Across a thin wall, round a plate's rim or along a
      // crease it is a good part of the spacing, and standing off the plane
      // says nothing there.
      sorted.clear();
      for (size_t j = 0; j < (inliers >= 5 ? inliers : m); ++j) sorted.push_back(off_plane(ids[j]));
      spread[r] = median_in_place(sorted);
      double d = 0;
      for (int a = 0; a < 3; ++a) d += (xyz[3 * r + a] - plane.point[a]) * plane.normal[a];
      off[r] = std::abs(d);
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
    for (size_t r = from; r < to; ++r) {
      around.clear();
      around_off.clear();
      around_gap.clear();
      for (size_t j = r * k; j < (r + 1) * k; ++j) {
        if (neighbours[j] == UINT32_MAX) continue;
        around.push_back(reach[neighbours[j]]);
        around_gap.push_back(gap[neighbours[j]]);
        if (off[neighbours[j]] >= 0) around_off.push_back(off[neighbours[j]]);
      }
      const double local = std::max(median_in_place(around), reach_floor);
      if (!(local > 0)) continue;
      bool isolated = reach[r] > o.isolation * local;
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
      const bool piled = median_in_place(around_gap) < 0.6 * gap_floor;
      if (!isolated && !piled && off[r] >= 0 && off[r] > o.off_plane * local && off[r] > o.off_noise * median_in_place(around_off) &&
          off[r] > o.off_noise * spread[r]) {
        // The nearest neighbour nearer the plane: a second stray beside
        // this one does not count.
        double lower_gap = 0;
        for (size_t j = r * k; j < (r + 1) * k && lower_gap == 0; ++j) {
          const uint32_t q = neighbours[j];
          if (q == UINT32_MAX || !(off[q] >= 0 && off[q] < 0.5 * off[r])) continue;
          double d2 = 0;
          for (int a = 0; a < 3; ++a) d2 += std::pow(double{xyz[3 * r + a]} - xyz[3 * q + a], 2);
          lower_gap = std::sqrt(d2);
        }
        isolated = lower_gap == 0 || lower_gap > o.off_gap * std::max(median_in_place(around_gap), gap_floor);
      }
      if (isolated) keep[order[r]] = 0;
    }
  });
  s.isolated = static_cast<size_t>(std::count(keep.begin(), keep.end(), 0));
  // Over 100 bytes a point (the neighbour lists 64 of them) not needed by
  // the clusters' test, which builds its own.
  for (auto* figures : {&reach, &gap, &off, &spread}) std::vector<double>().swap(*figures);
  std::vector<uint32_t>().swap(neighbours);
  std::vector<uint32_t>().swap(rank_of);
  std::vector<float>().swap(ranked.xyz);

  // Clusters among the points left.
  // With no point isolated the rest is the input and so is its index (a
  // k-d tree over 10M points takes 6-11 s to build); otherwise the rest's
  // index is handed to the caller should no cluster be dropped.
  std::unique_ptr<PointIndex> built;
  if (s.isolated > 0) {
    out = subset(pc, keep);
    built = std::make_unique<PointIndex>(out);
  }
  const PointIndex& rest_index = built ? *built : index;
  const PointCloud& rest = rest_index.points();
  if (rest.size() > k) {
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
    built.reset();  // (it refers to `out`)
    out = pc;
    return nullptr;
  }
  if (stats) *stats = s;
  if (s.cluster_points > 0) {
    built.reset();
    out = subset(pc, keep);
  } else if (!built) {
    out = pc;
  }
  return built;
}

}  // namespace dbss
