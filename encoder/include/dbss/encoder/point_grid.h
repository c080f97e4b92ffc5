// Nearest-point queries near a known point, on a uniform grid of cells:
// shrink-wrap's warm-started searches, which the KD-tree answered by a
// descent of a dozen levels per query.
#pragma once

#include <cstdint>
#include <vector>

#include "dbss/encoder/point_index.h"

namespace dbss {

class PointGrid {
 public:
  // Bins the index's points into cubic cells of about `cell` (grown until
  // there are at most 8 cells per point).  Keeps a reference to `index`.
  PointGrid(const PointIndex& index, double cell);

  // The same point as index.nearest(q, hint), bit for bit: every point
  // whose distance to q (computed as the tree computes it) could be under
  // the hint's is read from the cells the hint's ball touches, and the
  // nearest is returned when no other is within 1e-5 of its squared
  // distance.  A near tie, or a ball over more than 64 cells, is left to
  // the tree, whose order among equals (and rounding) is its own.
  uint32_t nearest(const float q[3], uint32_t hint) const;

  // The same by slots, the points' places in the grid's own copy (in cell
  // order): a hint's and the answer's coordinates are then read next to the
  // cells searched (reading the hint from the cloud, in its random order,
  // was a third of a query's time on the bunny 35k).
  uint32_t nearest_slot(const float q[3], uint32_t hint_slot) const;
  const float* slot_xyz(uint32_t slot) const { return &xyz_[3 * size_t{slot}]; }
  uint32_t slot_of(uint32_t point) const { return slot_of_[point]; }
  uint32_t point_of(uint32_t slot) const { return id_[slot]; }

  // How many queries went to the tree (ties or wide balls): for tests.
  uint64_t tree_queries() const noexcept { return tree_queries_; }

 private:
  const PointIndex& index_;
  double origin_[3] = {0, 0, 0};
  double per_cell_ = 1;
  int n_[3] = {1, 1, 1};
  std::vector<uint32_t> start_;  // CSR: cell c's points are [start_[c], start_[c + 1])
  std::vector<float> xyz_;       // the points in cell order
  std::vector<uint32_t> id_;     // their indices in the cloud
  std::vector<uint32_t> slot_of_;  // a cloud index's place in xyz_
  mutable uint64_t tree_queries_ = 0;
};

}  // namespace dbss
