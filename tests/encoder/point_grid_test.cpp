#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "dbss/encoder/point_grid.h"
#include "dbss/encoder/point_index.h"

using namespace dbss;

// PointGrid::nearest must give the tree's answer bit for bit (shrink-wrap's
// output depends on it): random surface-like clouds with duplicated points
// (exact ties) and points on a lattice (many equal distances), queried from
// near and far with near and far hints.
TEST_CASE("PointGrid::nearest equals PointIndex::nearest, ties and far hints included", "[point_grid]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  for (int shape = 0; shape < 3; ++shape) {
    PointCloud pc;
    for (int i = 0; i < 6000; ++i) {
      float p[3];
      if (shape == 2) {
        // A lattice on a plane: many queries meet equal distances.
        p[0] = static_cast<float>(i % 80) * 0.025f, p[1] = static_cast<float>(i / 80) * 0.025f, p[2] = 0;
      } else {
        // A sphere's surface (shape 1 with every tenth point doubled).
        const float x = u(rng), y = u(rng), z = u(rng), r = std::sqrt(x * x + y * y + z * z) + 1e-6f;
        p[0] = x / r, p[1] = y / r, p[2] = z / r;
      }
      pc.xyz.insert(pc.xyz.end(), p, p + 3);
      if (shape == 1 && i % 10 == 0) pc.xyz.insert(pc.xyz.end(), p, p + 3);
    }
    const PointIndex index(pc);
    for (double cell : {0.01, 0.05, 0.3}) {
      const PointGrid grid(index, cell);
      size_t differ = 0;
      std::uniform_int_distribution<uint32_t> any(0, static_cast<uint32_t>(pc.size() - 1));
      for (int t = 0; t < 20000; ++t) {
        const uint32_t near = any(rng);
        float q[3];
        const float jitter = t % 3 == 0 ? 0.5f : t % 3 == 1 ? 0.02f : 0.0f;  // far, near, on a point
        for (int a = 0; a < 3; ++a) q[a] = pc.xyz[3 * size_t{near} + a] + jitter * u(rng);
        const uint32_t hint = t % 2 ? near : any(rng);
        differ += grid.nearest(q, hint) != index.nearest(q, hint);
      }
      CHECK(differ == 0);
    }
  }
}

// A degenerate shell asks for a cell of 0 or NaN, and a broken vertex can
// be NaN: the grid must still answer as the tree does (these counts
// overflowed int, and NaN queries indexed outside the offsets, before).
TEST_CASE("PointGrid with a cell of zero or NaN and non-finite queries answers as the tree", "[point_grid]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1, 1);
  PointCloud pc;
  for (int i = 0; i < 2000; ++i) pc.xyz.insert(pc.xyz.end(), {u(rng), u(rng), u(rng)});
  const PointIndex index(pc);
  for (double cell : {0.0, -1.0, std::nan(""), double{INFINITY}}) {
    const PointGrid grid(index, cell);
    for (int t = 0; t < 2000; ++t) {
      const float q[3] = {u(rng), u(rng), u(rng)};
      const uint32_t hint = static_cast<uint32_t>(t) % 2000;
      REQUIRE(grid.nearest(q, hint) == index.nearest(q, hint));
    }
    const float nan_q[3] = {std::nanf(""), 0, 0}, inf_q[3] = {0, INFINITY, 0};
    CHECK(grid.nearest(nan_q, 5) == index.nearest(nan_q, 5));
    CHECK(grid.nearest(inf_q, 5) == index.nearest(inf_q, 5));
  }
}
