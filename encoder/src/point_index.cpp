#include "dbss/encoder/point_index.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <nanoflann.hpp>

namespace dbss {

namespace {
// The tree's view of the points: while it is built, the cloud itself; after,
// a copy in the tree's leaf order (see PointIndex::Tree).
struct CloudAdaptor {
  const float* xyz;
  size_t count;
  size_t kdtree_get_point_count() const { return count; }
  float kdtree_get_pt(size_t i, size_t dim) const { return xyz[3 * i + dim]; }
  template <class B>
  bool kdtree_get_bbox(B&) const { return false; }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, CloudAdaptor>, CloudAdaptor, 3, uint32_t>;
}  // namespace

// The tree is built over the cloud as given; then its points are copied in
// the order the tree's leaves list them and the tree is pointed at the
// copy, its index list made the identity: a leaf's points are then read side
// by side instead of from all over the cloud (on 10M points in random order,
// nearly every point a search looked at missed the cache).  The searches do
// the same arithmetic on the same floats in the same order, and a hit's
// position in the copy maps back to the point's index: the same answers,
// ties included, as the tree over the cloud.
struct PointIndex::Tree {
  CloudAdaptor adaptor;
  dbss::Tree tree;
  std::vector<float> leaf_xyz;     // the points in leaf order
  std::vector<uint32_t> original;  // a leaf-order position's point index
  explicit Tree(const PointCloud& pc)
      : adaptor{pc.xyz.data(), pc.size()}, tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    original.swap(tree.vAcc);
    leaf_xyz.resize(3 * original.size());
    for (size_t p = 0; p < original.size(); ++p)
      for (int a = 0; a < 3; ++a) leaf_xyz[3 * p + a] = pc.xyz[3 * size_t{original[p]} + a];
    tree.vAcc.resize(original.size());
    std::iota(tree.vAcc.begin(), tree.vAcc.end(), 0u);
    adaptor.xyz = leaf_xyz.data();
  }
};

PointIndex::PointIndex(const PointCloud& points) : points_(points), tree_(std::make_unique<Tree>(points)) {}
PointIndex::~PointIndex() = default;

uint32_t PointIndex::nearest(const float q[3]) const {
  uint32_t i = 0;
  float d = 0;
  tree_->tree.knnSearch(q, 1, &i, &d);
  return tree_->original[i];
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
  BoundedNearest r{d * (1 + 1e-5f) + 1e-30f, UINT32_MAX};
  tree_->tree.findNeighbors(r, q, nanoflann::SearchParams());
  return r.index == UINT32_MAX ? hint : tree_->original[r.index];
}

size_t PointIndex::nearest_k(const float q[3], size_t k, uint32_t* indices, float* dist2) const {
  const size_t got = tree_->tree.knnSearch(q, k, indices, dist2);
  for (size_t j = 0; j < got; ++j) indices[j] = tree_->original[indices[j]];
  return got;
}

void PointIndex::within(const float q[3], float radius, std::vector<uint32_t>& out) const {
  std::vector<std::pair<uint32_t, float>> hits;
  nanoflann::SearchParams params;
  params.sorted = false;
  tree_->tree.radiusSearch(q, radius * radius, hits, params);  // L2_Simple works on squared distances
  out.clear();
  for (const auto& h : hits) out.push_back(tree_->original[h.first]);
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
