#include "dbss/encoder/point_grid.h"

#include <algorithm>
#include <cmath>

namespace dbss {

PointGrid::PointGrid(const PointIndex& index, double cell) : index_(index) {
  const PointCloud& pc = index.points();
  const size_t n = pc.size();
  if (n == 0) return;
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], double{pc.xyz[3 * i + a]}), hi[a] = std::max(hi[a], double{pc.xyz[3 * i + a]});
  // A surface fills a thin layer of the box, so most cells stay empty; the
  // cap keeps the offsets array (4 bytes a cell) near the points' size.
  // The count is checked in doubles before any cast: a degenerate shell
  // (no edges, or all its vertices at one spot) asks for a cell of 0 or NaN,
  // whose counts would overflow int.
  if (!(cell > 1e-30)) cell = 1e-30;
  for (;;) {
    double cells = 1;
    for (int a = 0; a < 3; ++a) cells *= std::floor((hi[a] - lo[a]) / cell) + 1;
    if (cells <= 8.0 * n + 64) break;
    cell *= 1.25;
  }
  for (int a = 0; a < 3; ++a) n_[a] = std::max(1, static_cast<int>((hi[a] - lo[a]) / cell) + 1);
  for (int a = 0; a < 3; ++a) origin_[a] = lo[a];
  per_cell_ = 1 / cell;
  const size_t cells = size_t(n_[0]) * n_[1] * n_[2];
  std::vector<uint32_t> of(n);
  start_.assign(cells + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    size_t c = 0;
    for (int a = 2; a >= 0; --a)
      c = c * n_[a] + std::min(n_[a] - 1, static_cast<int>((double{pc.xyz[3 * i + a]} - origin_[a]) * per_cell_));
    of[i] = static_cast<uint32_t>(c);
    ++start_[c + 1];
  }
  for (size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  std::vector<uint32_t> at(start_.begin(), start_.end() - 1);
  xyz_.resize(3 * n);
  id_.resize(n);
  slot_of_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const uint32_t k = at[of[i]]++;
    id_[k] = static_cast<uint32_t>(i), slot_of_[i] = k;
    for (int a = 0; a < 3; ++a) xyz_[3 * size_t{k} + a] = pc.xyz[3 * i + a];
  }
}

uint32_t PointGrid::nearest(const float q[3], uint32_t hint) const { return id_[nearest_slot(q, slot_of_[hint])]; }

uint32_t PointGrid::nearest_slot(const float q[3], uint32_t hint) const {
  // A non-finite query has no cell: the tree answers it as it always did.
  if (!(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]))) return ++tree_queries_, slot_of_[index_.nearest(q, id_[hint])];
  const float* h = &xyz_[3 * size_t{hint}];
  // Distances as nanoflann's L2_Simple_Adaptor sums them: in float, axis by
  // axis from zero (the build keeps fp-contract off).
  const auto dist2 = [q](const float* p) {
    float d = 0;
    for (int a = 0; a < 3; ++a) {
      const float diff = q[a] - p[a];
      d += diff * diff;
    }
    return d;
  };
  // A point outside the ball of this radius along some axis is at least
  // that far: its float distance, rounding included, exceeds the hint's
  // (the 1e-3 covers a few ulps many times over).
  const double r = std::sqrt(double{dist2(h)}) * (1 + 1e-3) + 1e-30;
  int c0[3], c1[3];
  long span = 1;
  for (int a = 0; a < 3; ++a) {
    const double lo = std::floor((double{q[a]} - r - origin_[a]) * per_cell_), hi = std::floor((double{q[a]} + r - origin_[a]) * per_cell_);
    c0[a] = static_cast<int>(std::clamp(lo, 0.0, double(n_[a] - 1)));
    c1[a] = static_cast<int>(std::clamp(hi, 0.0, double(n_[a] - 1)));
    span *= c1[a] - c0[a] + 1;
  }
  if (span > 64) {
    // A hint far away (the first iteration's, from the vertex before):
    // the nearest of the points in the cells around q's, if nearer, bounds
    // the search instead.  Any hint gives the same answer.
    float hd = dist2(h);
    uint32_t better = UINT32_MAX;
    int c[3];
    for (int a = 0; a < 3; ++a)
      c[a] = static_cast<int>(std::clamp(std::floor((double{q[a]} - origin_[a]) * per_cell_), 0.0, double(n_[a] - 1)));
    for (int z = std::max(0, c[2] - 1); z <= std::min(n_[2] - 1, c[2] + 1); ++z)
      for (int y = std::max(0, c[1] - 1); y <= std::min(n_[1] - 1, c[1] + 1); ++y) {
        const size_t row = (size_t(z) * n_[1] + y) * n_[0];
        const uint32_t e = start_[row + std::min(n_[0] - 1, c[0] + 1) + 1];
        for (uint32_t k = start_[row + std::max(0, c[0] - 1)]; k < e; ++k)
          if (const float d = dist2(&xyz_[3 * size_t{k}]); d < hd) hd = d, better = k;
      }
    if (better != UINT32_MAX) return nearest_slot(q, better);
    return ++tree_queries_, slot_of_[index_.nearest(q, id_[hint])];
  }
  float best = INFINITY, second = INFINITY;
  uint32_t at = UINT32_MAX;
  for (int z = c0[2]; z <= c1[2]; ++z)
    for (int y = c0[1]; y <= c1[1]; ++y) {
      // A row's cells are consecutive, and so are their points.
      const size_t row = (size_t(z) * n_[1] + y) * n_[0];
      const uint32_t e = start_[row + c1[0] + 1];
      for (uint32_t k = start_[row + c0[0]]; k < e; ++k) {
        const float d = dist2(&xyz_[3 * size_t{k}]);
        if (d < best) second = best, best = d, at = k;
        else if (d < second) second = d;
      }
    }
  // Two points this close could be ordered differently by the tree (its
  // subtree bounds round within a few ulps): the tree decides.
  if (at == UINT32_MAX || second <= best * (1 + 1e-5f)) return ++tree_queries_, slot_of_[index_.nearest(q, id_[hint])];
  return at;
}

}  // namespace dbss
