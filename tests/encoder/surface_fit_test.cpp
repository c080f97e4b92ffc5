// The local surface fit the sampler takes its distances to (surface_fit.h):
// on a noisy sphere it lands closer to the true surface than the line's
// first hit among the points; it keeps to the sheet the hit found; a stray
// point among the surface's points does not pull it.
#include <catch2/catch.hpp>

#include "../sampled_shapes.h"

#include <cmath>
#include <numbers>
#include <random>

#include "dbss/encoder/point_index.h"
#include "dbss/encoder/sampling.h"
#include "dbss/encoder/surface_fit.h"

using namespace dbss;

namespace {

using test::noisy_sphere;

// A grid of points on the plane z = h, spacing `d`, over [-1, 1]^2.
void add_plane(PointCloud& pc, double h, double d) {
  for (double x = -1; x <= 1; x += d)
    for (double y = -1; y <= 1; y += d) pc.xyz.insert(pc.xyz.end(), {float(x), float(y), float(h)});
}

}  // namespace

TEST_CASE("surface fit: on a noisy sphere the fitted distance beats the first hit") {
  // 20k points: spacing about 0.025; noise 0.005 along the radius.
  const PointCloud pc = noisy_sphere(20000, 0.005, 3);
  const PointIndex index(pc);
  std::mt19937 rng(9);
  std::normal_distribution<double> g(0, 1);
  double hit2 = 0, fit2 = 0;
  int fitted = 0;
  const int trials = 400;
  for (int i = 0; i < trials; ++i) {
    // A vertex 0.05 off the sphere, its normal tilted up to ~10 degrees from
    // the radius, as a subdivision normal is.
    double dir[3] = {g(rng), g(rng), g(rng)};
    const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    for (double& c : dir) c /= len;
    double n[3] = {dir[0] + 0.1 * g(rng), dir[1] + 0.1 * g(rng), dir[2] + 0.1 * g(rng)};
    const double nl = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& c : n) c /= nl;
    const double p[3] = {1.05 * dir[0], 1.05 * dir[1], 1.05 * dir[2]};
    // The exact distance along n from p to the unit sphere (the nearer root).
    const double b = p[0] * n[0] + p[1] * n[1] + p[2] * n[2];
    const double c = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - 1;
    const double exact = -b + std::sqrt(b * b - c);
    const Sample hit = sample_displacement(index, p, n, 0.1, 0.2, false);
    const Sample fit = sample_displacement(index, p, n, 0.1, 0.2, true);
    REQUIRE_FALSE(hit.fitted);
    fitted += fit.fitted;
    hit2 += std::pow(hit.distance - exact, 2);
    fit2 += std::pow(fit.distance - exact, 2);
  }
  const double hit_rms = std::sqrt(hit2 / trials), fit_rms = std::sqrt(fit2 / trials);
  INFO("hit RMS " << hit_rms << ", fit RMS " << fit_rms << ", fitted " << fitted);
  CHECK(fitted == trials);
  // Measured: hit 3.8e-3 (about the noise), fit 2.5e-3.  Bounds: 0.8x the
  // hit's error and 1.3x the fit's measured error.
  CHECK(fit_rms < 0.8 * hit_rms);
  CHECK(fit_rms < 3.2e-3);
}

TEST_CASE("surface fit: it keeps to the sheet the hit found, and a stray point does not pull it") {
  // Two parallel sheets 0.1 apart (4 point spacings), a vertex between
  // them nearer the lower one.
  PointCloud pc;
  add_plane(pc, 0.0, 0.025);
  add_plane(pc, 0.1, 0.025);
  const PointIndex two(pc);
  const double p[3] = {0.0125, 0.0125, 0.04}, down[3] = {0, 0, -1}, up[3] = {0, 0, 1};
  FitScratch s;
  const SurfaceFit lower = fit_height(two, p, down, 0.04, kFitPoints, s);
  REQUIRE(lower.ok);
  CHECK(lower.height == Approx(0.04).margin(1e-9));
  const SurfaceFit upper = fit_height(two, p, up, 0.06, kFitPoints, s);
  REQUIRE(upper.ok);
  CHECK(upper.height == Approx(0.06).margin(1e-9));

  // One plane and a point 0.01 above it beside the line (within the fit's
  // band, so only the robust weights can reject it).
  PointCloud one;
  add_plane(one, 0.0, 0.025);
  one.xyz.insert(one.xyz.end(), {0.02f, 0.0f, 0.01f});
  const PointIndex with_stray(one);
  const double q[3] = {0.0, 0.0, 0.05};
  const SurfaceFit f = fit_height(with_stray, q, down, 0.05, kFitPoints, s);
  REQUIRE(f.ok);
  INFO("height " << f.height);
  CHECK(std::abs(f.height - 0.05) < 1e-6);
}

TEST_CASE("surface fit: on a clean cloud a bend of the surface is rounded over less than the neighbourhood") {
  // A roof z = s |x| bending by 30 degrees at x = 0, 10k area-uniform points
  // on [-1, 1]^2 (spacing about 0.02; the fit's 24 points reach about 0.055),
  // no noise.  Vertical lines 0 to 3 spacings from the ridge, 0.02 above the
  // roof: every point is exactly on the surface, so the fit's error there is
  // its rounding of the bend (bench/floor_probe --regions: on faceted true
  // meshes most of the finest level's excess over advancing front).
  const double s = std::tan(15 * std::numbers::pi / 180);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  PointCloud pc;
  for (int i = 0; i < 10000; ++i) {
    const double x = u(rng), y = u(rng);
    pc.xyz.insert(pc.xyz.end(), {float(x), float(y), float(s * std::abs(x))});
  }
  const PointIndex index(pc);
  const double n[3] = {0, 0, 1};
  double sum = 0;
  const int trials = 200;
  for (int i = 0; i < trials; ++i) {
    const double x = 0.06 * (i + 0.5) / trials * (i % 2 ? 1 : -1), y = 0.5 * u(rng);
    const double p[3] = {x, y, s * std::abs(x) + 0.02};
    const Sample f = sample_displacement(index, p, n, 0.02, 0.1);
    REQUIRE(f.fitted);
    sum += std::abs(f.distance + 0.02);
  }
  const double mean = sum / trials;
  INFO("mean |fitted - exact| " << mean);
  // Measured: the narrow kernel ((1 - r^2)^2, before the twelfth session)
  // 3.01e-4; the tight kernel of clean clouds ((1 - r^2)^4) 2.47e-4.  The
  // bound sits between them.
  CHECK(mean < 2.75e-4);
}

TEST_CASE("surface fit: mild noise, below points_are_noisy, is told from a clean cloud's own shape") {
  // The unit sphere, 20k points (the 24-point neighbourhood's radius about
  // 0.07), with noise of 5e-4 along the radius: a tenth of the scatter
  // points_are_noisy calls noise (2% of the radius), so before issue 15's
  // h12-mild gate the sampler fit it with the tight kernel.  Without noise
  // the cloud is quiet; with it, not, and there the narrow kernel's fit is
  // the closer one (no bend to keep, twice the points averaged).
  const PointCloud clean = noisy_sphere(20000, 0, 3), mild = noisy_sphere(20000, 5e-4, 3);
  const PointIndex clean_index(clean), mild_index(mild);
  CHECK(points_are_quiet(clean_index));
  CHECK_FALSE(points_are_noisy(mild_index));
  CHECK_FALSE(points_are_quiet(mild_index));
  // The same lines as the sampler's, fit with each kernel.
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0, 1);
  double narrow2 = 0, tight2 = 0;
  const int trials = 400;
  for (int i = 0; i < trials; ++i) {
    double dir[3] = {g(rng), g(rng), g(rng)};
    const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    for (double& c : dir) c /= len;
    const double p[3] = {1.02 * dir[0], 1.02 * dir[1], 1.02 * dir[2]};
    SampleScratch scratch;
    const Sample narrow = sample_displacement(mild_index, p, dir, 0.05, 0.05, scratch, true, nullptr, false, false);
    const Sample tight = sample_displacement(mild_index, p, dir, 0.05, 0.05, scratch, true, nullptr, false, true);
    REQUIRE(narrow.fitted);
    REQUIRE(tight.fitted);
    narrow2 += std::pow(narrow.distance + 0.02, 2);
    tight2 += std::pow(tight.distance + 0.02, 2);
  }
  const double narrow_rms = std::sqrt(narrow2 / trials), tight_rms = std::sqrt(tight2 / trials);
  INFO("narrow RMS " << narrow_rms << ", tight RMS " << tight_rms);
  CHECK(narrow_rms < 0.9 * tight_rms);
}

TEST_CASE("surface fit: the noise figures from one probe walk") {
  // point_noise walks the probes once for all three figures: on the unit
  // sphere with noise of 3e-3 along the radius (about 4% of the 24-point
  // neighbourhood's radius) the cloud is noisy, not quiet, and the noise
  // is about the noise's own deviation (the fits' RMS scatter, less the
  // degrees of freedom the fit takes); without noise, quiet, not noisy and
  // near 0.  Mixing up the figures (the scatter over the radius for the
  // noise, or the ratio's median for the scatter's) fails these bounds.
  const double sigma = 3e-3;
  const PointCloud noisy = noisy_sphere(20000, sigma, 5), clean = noisy_sphere(20000, 0, 5);
  const PointIndex noisy_index(noisy), clean_index(clean);
  const PointNoise n = point_noise(noisy_index), c = point_noise(clean_index);
  INFO("noisy: noise " << n.noise << "; clean: noise " << c.noise);
  CHECK(n.noisy);
  CHECK_FALSE(n.quiet);
  CHECK(n.noise > 0.6 * sigma);
  CHECK(n.noise < 1.2 * sigma);
  CHECK_FALSE(c.noisy);
  CHECK(c.quiet);
  CHECK(c.noise < 0.05 * sigma);
  // The one-figure calls agree with it.
  CHECK(points_are_noisy(noisy_index) == n.noisy);
  CHECK(points_are_quiet(noisy_index) == n.quiet);
  CHECK(points_noise(noisy_index) == n.noise);
}
