// Scan clean-up before carving: points far from the surface their
// neighbours sample (a scanner's stray returns, dust, reflections) and small
// clusters of points away from the main object.  Each becomes a tiny closed
// surface, or a spike, once carved, so they go first.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "dbss/encoder/point_index.h"
#include "dbss/encoder/point_input.h"

namespace dbss {

struct OutlierOptions {
  bool enabled = true;  // false: keep every point (`--keep-outliers`, data known to be clean)
  // A point is isolated when its mean distance to its k nearest points is
  // over `isolation` times the median of the same figure at those k points:
  // a ratio to the neighbourhood rather than to the whole cloud, so the
  // sparse side of an uneven scan is not taken for outliers.  16 rather
  // than 8 so that strays side by side, each one of the other's
  // neighbours, still stand out against a plane of surface points.
  uint32_t k = 16;
  double isolation = 5.0;
  // Or when it lies farther than `off_plane` times that median from the
  // least-squares plane of those k points, and farther than `off_noise`
  // times the median of the same distance at those points (on a noisy
  // scan every point stands off its neighbours' plane; a stray one stands
  // off much farther than they do).
  // And only when its nearest point is farther than `off_gap` times the
  // median of the same distance at those points (a point on a crease is
  // off the plane of both sides but as close to its nearest point as any).
  double off_plane = 0.75;
  double off_noise = 5.0;
  double off_gap = 2.0;
  // Clusters: points linked when closer than `link` times the cloud's
  // 99th-percentile spacing (distance to the nearest point), about the gap
  // the carving bridges, so a cluster is what would carve into a separate
  // solid; one is dropped when it holds under `min_cluster_share` of the
  // points.  The high percentile keeps the sparse side of an uneven scan in
  // one piece.
  double link = 3.0;
  double min_cluster_share = 0.02;
  unsigned threads = 1;  // for the per-point tests; the result is the same on any number
};

struct OutlierStats {
  size_t points_in = 0;
  size_t duplicates = 0;        // exact repeats of an earlier point, merged into it
  size_t isolated = 0;          // points dropped as isolated
  size_t clusters = 0;          // clusters found among the rest
  size_t clusters_dropped = 0;  // of them, dropped as too small
  size_t cluster_points = 0;    // points in the dropped clusters
  bool clustered = false;       // the cluster test ran (clusters - clusters_dropped is what stayed)
  size_t kept() const { return points_in - duplicates - isolated - cluster_points; }
};

// The points that survive both tests, in input order (normals kept along
// when present), exact duplicates merged into their first occurrence.  With options.enabled false, a copy of `points`.  `index`
// must be built on `points`.  Never returns fewer than 4 points unless given
// fewer: if the tests would leave fewer, nothing is dropped.
PointCloud remove_outliers(const PointIndex& index, const OutlierOptions& options = {}, OutlierStats* stats = nullptr);

// The same, the kept points written to `out`.  Returns an index built on
// `out` when the tests built one on the way (the clusters' test needs one
// over the points left after the isolated ones), null otherwise (nothing
// dropped, or the last test dropped more): the caller builds one only then.
// The index refers to `out`, which must stay where it is while it is used.
std::unique_ptr<PointIndex> remove_outliers(const PointIndex& index, const OutlierOptions& options, OutlierStats* stats,
                                            PointCloud& out);

// Connected clusters of the points: two points are in one cluster when a
// chain of points, each within `radius` of the next, joins them.  Returns a
// cluster id per point (0..count-1, ids ordered by first point) and the
// count through `count`.
std::vector<uint32_t> point_clusters(const PointIndex& index, double radius, uint32_t* count);

// The radius remove_outliers() links clusters at, for `options`.
double cluster_radius(const PointIndex& index, const OutlierOptions& options = {});

}  // namespace dbss
