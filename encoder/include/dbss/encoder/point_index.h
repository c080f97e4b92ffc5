// Nearest-point queries on a point cloud (nanoflann KD-tree, built once).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "dbss/encoder/point_input.h"

namespace dbss {

class PointIndex {
 public:
  // Keeps a reference to `points`, which must outlive the index.
  explicit PointIndex(const PointCloud& points);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  // Index of the point closest to q (ties: any).
  uint32_t nearest(const float q[3]) const;
  // The same, faster when `hint` (any point's index) is near q: a vertex's
  // nearest point from the last iteration.  Ties may resolve differently
  // from nearest() only between points whose distances to q differ by
  // rounding.
  uint32_t nearest(const float q[3], uint32_t hint) const;
  // The k nearest points, closest first; returns how many were found.
  size_t nearest_k(const float q[3], size_t k, uint32_t* indices, float* dist2) const;
  // Indices of the points within `radius` of q (unordered).
  void within(const float q[3], float radius, std::vector<uint32_t>& out) const;
  const PointCloud& points() const noexcept { return points_; }

 private:
  struct Tree;
  const PointCloud& points_;
  std::unique_ptr<Tree> tree_;
};

// A spacing statistic of the cloud: the `quantile` (0..1) of every sampled
// point's distance to its k-th nearest neighbour (over up to 4096 points).
double point_spacing(const PointIndex& index, size_t k, double quantile);

}  // namespace dbss
