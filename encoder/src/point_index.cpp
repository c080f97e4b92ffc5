#include "dbss/encoder/point_index.h"

#include <algorithm>
#include <cmath>
#include <nanoflann.hpp>

namespace dbss {

namespace {
struct CloudAdaptor {
  const PointCloud& pc;
  size_t kdtree_get_point_count() const { return pc.size(); }
  float kdtree_get_pt(size_t i, size_t dim) const { return pc.xyz[3 * i + dim]; }
  template <class B>
  bool kdtree_get_bbox(B&) const { return false; }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, CloudAdaptor>, CloudAdaptor, 3, uint32_t>;
}  // namespace

struct PointIndex::Tree {
  CloudAdaptor adaptor;
  dbss::Tree tree;
  explicit Tree(const PointCloud& pc) : adaptor{pc}, tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}
};

PointIndex::PointIndex(const PointCloud& points) : points_(points), tree_(std::make_unique<Tree>(points)) {}
PointIndex::~PointIndex() = default;

uint32_t PointIndex::nearest(const float q[3]) const {
  uint32_t i = 0;
  float d = 0;
  tree_->tree.knnSearch(q, 1, &i, &d);
  return i;
}

namespace {
// A one-point result set whose search starts from a bound instead of from
// infinity: nanoflann's KNNResultSet for one point but for that start.
struct BoundedNearest {
  float best;
  uint32_t index;
  bool addPoint(float dist, uint32_t i) {
    if (dist < best) best = dist, index = i;
    return true;
  }
  float worstDist() const { return best; }
  bool full() const { return true; }
};
}  // namespace

uint32_t PointIndex::nearest(const float q[3], uint32_t hint) const {
  // The hint's distance, as nanoflann computes it, a little enlarged: every
  // subtree holding a point as near as the hint is still searched (the
  // enlargement covers the rounding of the subtrees' lower bounds), so the
  // answer is a full search's; those farther are skipped.
  const float* p = &points_.xyz[3 * size_t{hint}];
  float d = 0;
  for (int a = 0; a < 3; ++a) {
    const float diff = q[a] - p[a];
    d += diff * diff;
  }
  BoundedNearest r{d * (1 + 1e-5f) + 1e-30f, hint};
  tree_->tree.findNeighbors(r, q, nanoflann::SearchParams());
  return r.index;
}

size_t PointIndex::nearest_k(const float q[3], size_t k, uint32_t* indices, float* dist2) const {
  return tree_->tree.knnSearch(q, k, indices, dist2);
}

void PointIndex::within(const float q[3], float radius, std::vector<uint32_t>& out) const {
  std::vector<std::pair<uint32_t, float>> hits;
  nanoflann::SearchParams params;
  params.sorted = false;
  tree_->tree.radiusSearch(q, radius * radius, hits, params);  // L2_Simple works on squared distances
  out.clear();
  for (const auto& h : hits) out.push_back(h.first);
}

double point_spacing(const PointIndex& index, size_t k, double quantile) {
  const PointCloud& pc = index.points();
  const size_t n = pc.size();
  if (n <= k) return 0;
  const size_t samples = std::min<size_t>(n, 4096);
  std::vector<double> d;
  d.reserve(samples);
  std::vector<uint32_t> idx(k + 1);
  std::vector<float> dist(k + 1);
  for (size_t s = 0; s < samples; ++s) {
    const size_t i = s * n / samples;
    const size_t got = index.nearest_k(&pc.xyz[3 * i], k + 1, idx.data(), dist.data());
    if (got == k + 1) d.push_back(std::sqrt(double{dist[k]}));
  }
  if (d.empty()) return 0;
  const size_t at = std::min(d.size() - 1, static_cast<size_t>(quantile * (d.size() - 1)));
  std::nth_element(d.begin(), d.begin() + at, d.end());
  return d[at];
}

}  // namespace dbss
