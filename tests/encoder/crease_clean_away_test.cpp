// A tagged file's samples away from its features (CreaseOptions::
// clean_away, sampling.cpp): where the fit's own points all face the
// line's way, the sample is a clean cloud's, with the tight kernel and the
// facet hit; before, a file with any crease tag sampled every vertex
// one-sided with the narrow kernel, on a machined part's faces too.
#include <catch2/catch.hpp>

#include "../sampled_shapes.h"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "dbss/encoder/crease_align.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/sampling.h"

using namespace dbss;

namespace {

// The roof z = s |x| bending by 30 degrees at x = 0 (under the crease
// angle: every point's normal within 15 degrees of the vertical), 10k
// area-uniform points on [-1, 1]^2 (spacing about 0.02), no noise; as
// facet_hit_test samples it.
PointCloud roof(double s) { return test::roof_cloud(s); }

// Mean |sampled - exact| over vertical lines 1 to 3 spacings from the
// ridge, 0.02 above the roof, sampled with `sides`.
double mean_error(const PointIndex& index, double s, const PointSides* sides) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const double n[3] = {0, 0, 1};
  SampleScratch scratch;
  double sum = 0;
  const int trials = 200;
  for (int i = 0; i < trials; ++i) {
    const double x = (0.02 + 0.04 * (i + 0.5) / trials) * (i % 2 ? 1 : -1), y = u(rng);
    const double p[3] = {x, y, s * std::abs(x) + 0.02};
    const Sample f = sample_displacement(index, p, n, 0.02, 0.1, scratch, true, sides, false, true);
    sum += std::abs(f.distance + 0.02);
  }
  return sum / trials;
}

}  // namespace

TEST_CASE("a tagged file's sample whose fit's points all agree takes the clean cloud's tight kernel and facet hit") {
  const double s = std::tan(15 * std::numbers::pi / 180);
  const PointCloud pc = roof(s);
  const PointIndex index(pc);
  const std::vector<float> normals = estimate_point_normals(index, 1);
  PointSides sides{&normals, std::cos(30 * std::numbers::pi / 180), false};
  const double clean = mean_error(index, s, nullptr);
  sides.clean_where_agreed = false;  // every sample one-sided (before)
  const double one_sided = mean_error(index, s, &sides);
  sides.clean_where_agreed = true;
  const double away = mean_error(index, s, &sides);
  INFO("mean |sampled - exact|: no sides " << clean << ", one-sided everywhere " << one_sided << ", clean where agreed " << away);
  // Measured: no sides 1.849e-5, clean where agreed 1.852e-5 (the
  // cylinder's hit is still taken from the agreeing points, which a few
  // lines' neighbourhoods beside the ridge lack), one-sided everywhere
  // 8.48e-5: the narrow kernel rounds the bend.
  CHECK(away < 1.05 * clean);
  CHECK(away < 4e-5);  // facet_hit_test's bound for a clean cloud
  CHECK(one_sided > 2 * away);
}
