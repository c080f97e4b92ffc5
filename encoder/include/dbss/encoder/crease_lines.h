// The control mesh's tagged crease edges as segments, for asking whether a
// point lies within reach of one: the sampler's wedge (sampling.cpp) fits
// two planes where the points show two sides, which a tightly curved smooth
// region can pass for; tied to the tags, it fires only beside a crease.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/point_index.h"
#include "dbss/format/container.h"

namespace dbss {

class CreaseLines {
 public:
  CreaseLines() = default;
  // The edges of `control` tagged in `creases` (canonical edge order).  Each
  // segment reaches `slack` times its length plus the radius of the
  // `neighbourhood` points nearest its midpoint (the wedge's own
  // neighbourhood there): refined crease lines bow off their control chord
  // (a curved feature) and a sample sees the feature from a neighbourhood
  // away.  Empty when no edge is tagged or the mesh is not manifold.
  CreaseLines(const TriangleMesh& control, const format::Creases& creases, const PointIndex& points,
              double slack, size_t neighbourhood);
  bool empty() const noexcept { return segments_.empty(); }
  size_t size() const noexcept { return segments_.size(); }
  // True when p is within reach of a tagged segment.
  bool near(const double p[3]) const;

 private:
  struct Segment {
    double a[3], b[3];
    double reach;
  };
  uint64_t cell_key(int64_t x, int64_t y, int64_t z) const;
  std::vector<Segment> segments_;
  double cell_ = 1;
  std::unordered_map<uint64_t, std::vector<uint32_t>> grid_;
};

}  // namespace dbss
