// Issue 15's level targets on shapes built here, against their exact
// surfaces: no level farther from the true surface than the one before
// (within 2%), and levels past the points' density cheap.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "../sampled_shapes.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/triangle_tree.h"
#include "dbss/measure/surface_samples.h"

using namespace dbss;

namespace {

// Two-sided mean distance between a level and the zero set of `sdf`: from
// area-uniform samples of the level, |sdf| (exact for the tori's distance
// functions); from fresh points of the true surface, the exact distance to
// the level's triangles.
double two_sided(const TriangleMesh& level, const test::Shape& s, const std::vector<double>& truth_points) {
  const std::vector<double> on_level = sample_surface(level, truth_points.size() / 3, 5);
  double to_truth = 0, to_level = 0;
  for (size_t i = 0; i < on_level.size(); i += 3) to_truth += std::abs(s.sdf(on_level[i], on_level[i + 1], on_level[i + 2]));
  const TriangleTree tree(level);
  for (size_t i = 0; i < truth_points.size(); i += 3) to_level += tree.distance(&truth_points[i]);
  return 0.5 * (to_truth / static_cast<double>(on_level.size() / 3) + to_level / static_cast<double>(truth_points.size() / 3));
}

// A shape's scan of `points` points (sampling seed `seed`) and, from another
// seed, kTruthPoints points of its true surface for two_sided.
struct Scan {
  PointCloud points;
  std::vector<double> truth;
};

// The measure's own noise must sit well under the 2% it checks: with 20,000
// samples a side, level 5 of the sparse tori came out 2.0-3.1% farther than
// level 4 on 3 of 14 sampling seeds (torus 5 and 6, double torus 2 and 4),
// and 0.0-1.6% on all 14 with 200,000 (bench/level_rise_probe): the same
// meshes, a mean over ten times the samples.
constexpr size_t kTruthPoints = 200000;

Scan scan_of(const test::Shape& s, size_t points, uint32_t seed = 7) {
  Scan scan;
  scan.points = test::sample_sdf(s.sdf, s.lo, s.hi, points, seed);
  const PointCloud truth = test::sample_sdf(s.sdf, s.lo, s.hi, kTruthPoints, 99);
  scan.truth.assign(truth.xyz.begin(), truth.xyz.end());
  return scan;
}

// Level l of `e` against the true surface, over the encoding's diagonal.
double level_error(const Encoding& e, uint32_t l, const test::Shape& s, const std::vector<double>& truth_points) {
  const TriangleMesh level{e.levels.positions[l], e.levels.triangles[l]};
  return two_sided(level, s, truth_points) / e.diagonal;
}

}  // namespace

TEST_CASE("levels against the true surface: no level farther than the one before, and levels past the points cheap") {
  // 3,000 points: the control mesh's level 2 or 3 already has more vertices
  // than points, so levels 3-5 are past the points' density.  Before issue
  // 15's fixes the fit's own error was coded as detail there and the error
  // rose from level to level.
  // Seed 7 for both, and the seed of each that rose most with 20,000
  // samples a side (torus 6: 3.1%, double torus 4: 2.3%).
  const std::vector<test::Shape> shapes = test::genus_shapes();
  const std::vector<std::pair<std::string, uint32_t>> cases = {{"torus", 7}, {"torus", 6}, {"double torus", 7}, {"double torus", 4}};
  for (const auto& c : cases) {
    // Plain names, not a structured binding: clang 14 cannot capture one in a lambda.
    const std::string& name = c.first;
    const uint32_t seed = c.second;
    const test::Shape& s = *std::find_if(shapes.begin(), shapes.end(), [&](const test::Shape& x) { return name == x.name; });
    INFO(name << ", seed " << seed);
    const Scan scan = scan_of(s, 3000, seed);
    const PointCloud& pc = scan.points;
    EncodeOptions o;
    o.levels = 5;
    auto e = encode_points(pc, o);
    REQUIRE(e.ok());
    const Encoding& enc = e.value();
    double previous = 0;
    for (uint32_t l = 0; l <= 5; ++l) {
      const double error = level_error(enc, l, s, scan.truth);
      INFO("level " << l << ": " << enc.levels.positions[l].size() / 3 << " vertices, error " << error << " of the diagonal, previous "
                    << previous << ", prefix " << prefix_bytes(enc, l) << " bytes");
      if (l > 0) CHECK(error <= 1.02 * previous);
      // Once the level before has more vertices than points, this one costs
      // at most half as much again.
      if (l > 0 && enc.levels.positions[l - 1].size() / 3 > pc.size())
        CHECK(prefix_bytes(enc, l) <= 1.5 * static_cast<double>(prefix_bytes(enc, l - 1)));
      previous = error;
    }
  }
}

TEST_CASE("the control mesh chosen by rate-distortion is never worse against the true surface than the default") {
  // EncodeOptions::choose_control also encodes over a quarter of the default
  // faces and keeps it only when, measured against the points, it reaches
  // every level of the default in no more bytes.  Here the same must hold
  // against the exact surface: at each level of the default encoding, the
  // kept encoding's curve (log bytes against log error, as rd_bench
  // interpolates) comes within 3% of that error in no more bytes.  A rule
  // that kept a control mesh too coarse for the shape (the levels crossing
  // the points' density at too few vertices) fails at the finest level.
  for (const test::Shape& s : test::genus_shapes()) {
    const std::string name = s.name;
    if (name != "torus" && name != "double torus") continue;
    INFO(name);
    const Scan scan = scan_of(s, 3000);
    const PointCloud& pc = scan.points;
    EncodeOptions o;
    o.levels = kAutoLevels;
    o.choose_control = false;
    auto fixed = encode_points(pc, o);
    o.choose_control = true;
    auto chosen = encode_points(pc, o);
    REQUIRE(fixed.ok());
    REQUIRE(chosen.ok());
    const Encoding& f = fixed.value();
    const Encoding& c = chosen.value();
    INFO("choice: " << c.control_choice);
    CHECK(!c.control_choice.empty());
    CHECK(f.control_choice.empty());
    const size_t default_faces = f.stages.control.triangle_count(), kept_faces = c.stages.control.triangle_count();
    const bool coarse = kept_faces != default_faces;
    // "kept N faces ..." for the quarter; otherwise the default, and why.
    if (coarse) CHECK(c.control_choice.rfind("kept " + std::to_string(kept_faces) + " faces", 0) == 0);
    else CHECK(c.control_choice.find("the default") != std::string::npos);
    if (!coarse) {  // the default kept: the very same control mesh and levels (only `meta` says more)
      CHECK(c.contents.control_mesh == f.contents.control_mesh);
      CHECK(c.contents.level_data == f.contents.level_data);
    }
    const auto curve = [&](const Encoding& e) {
      std::vector<std::pair<double, double>> out;  // (bytes, error)
      for (uint32_t l = 0; l <= e.level_count; ++l)
        out.emplace_back(static_cast<double>(prefix_bytes(e, l)), level_error(e, l, s, scan.truth));
      return out;
    };
    const auto cf = curve(f), cc = curve(c);
    for (size_t l = 0; l < cf.size(); ++l) {
      const double target = 1.03 * cf[l].second;
      double reached = -1;
      for (size_t i = 0; i < cc.size(); ++i) {
        if (!(cc[i].second <= target)) continue;
        if (i == 0) {
          reached = cc[0].first;
          break;
        }
        const double t = (std::log(target) - std::log(cc[i - 1].second)) / (std::log(cc[i].second) - std::log(cc[i - 1].second));
        reached = std::exp(std::log(cc[i - 1].first) + t * (std::log(cc[i].first) - std::log(cc[i - 1].first)));
        break;
      }
      INFO("default level " << l << ": " << cf[l].first << " bytes, error " << cf[l].second << "; kept " << kept_faces
                            << " faces reaches it in " << reached << " bytes");
      CHECK(reached > 0);
      CHECK(reached <= cf[l].first);
    }
  }
}

// The torus scanned with 8,000 points and Gaussian noise of 1e-3 of the
// diagonal per coordinate (seed 11; `noise` for another): the noisy cloud of
// the tests below.
static Scan noisy_torus_scan(const test::Shape& s, double noise = 1e-3) {
  Scan scan = scan_of(s, 8000);
  PointCloud& pc = scan.points;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < pc.xyz.size(); ++i) lo[i % 3] = std::min(lo[i % 3], double{pc.xyz[i]}), hi[i % 3] = std::max(hi[i % 3], double{pc.xyz[i]});
  const double diagonal = std::sqrt(std::pow(hi[0] - lo[0], 2) + std::pow(hi[1] - lo[1], 2) + std::pow(hi[2] - lo[2], 2));
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, noise * diagonal);
  for (float& x : pc.xyz) x = static_cast<float>(x + normal(rng));
  return scan;
}

TEST_CASE("a noisy cloud: no level farther from the true surface than the one before, to level 5") {
  // Gaussian noise of 1e-3 of the diagonal per coordinate.  The levels past
  // the points store zeros, and the butterfly turns the vertices' leftover
  // noise into a wavier surface.  The wider fit on noise (surface_fit.cpp,
  // kWiderAgreement) brought the rise on the 30k-point rd_bench clouds to
  // 0.1-1.7%; on this sparser torus (8,000 points) it measured, with it,
  // 0.29, 0.45, 0.92, 1.036, 1.017 from level to level: issue 15's 2% is not
  // met here yet, so the bound below is 5% past level 3 (a regression guard)
  // and the fall to level 3 must hold.
  const test::Shape s = test::genus_shapes()[1];  // torus
  INFO(s.name);
  Scan scan = noisy_torus_scan(s);
  PointCloud& pc = scan.points;
  EncodeOptions o;
  o.levels = 5;
  auto e = encode_points(pc, o);
  REQUIRE(e.ok());
  const Encoding& enc = e.value();
  double previous = 0;
  for (uint32_t l = 0; l <= 5; ++l) {
    const double error = level_error(enc, l, s, scan.truth);
    INFO("level " << l << ": " << enc.levels.positions[l].size() / 3 << " vertices, error " << error << " of the diagonal, previous "
                  << previous);
    if (l > 0 && l <= 3) CHECK(error <= 0.95 * previous);
    if (l > 3) CHECK(error <= 1.05 * previous);
    previous = error;
  }
}

TEST_CASE("a noisy cloud that stops before the points' density: not smoothed and not said to be") {
  // Smoothing acts only on the level that crosses the points' density
  // (levels.cpp); a file of one level over 8,000 noisy points has none, so
  // the kept control mesh must not be encoded again for it, and meta
  // control.choice must not claim smoothed levels (it did, review of the
  // eleventh session).  The file is the same with smoothing off.
  const test::Shape s = test::genus_shapes()[1];  // torus
  Scan scan = noisy_torus_scan(s);
  PointCloud& pc = scan.points;
  EncodeOptions o;
  o.levels = 1;
  auto on = encode_points(pc, o);
  o.smooth_noise = false;
  auto off = encode_points(pc, o);
  REQUIRE(on.ok());
  REQUIRE(off.ok());
  const Encoding& a = on.value();
  const Encoding& b = off.value();
  INFO("choice: " << a.control_choice);
  REQUIRE(a.levels.positions.size() == 2);
  CHECK(a.levels.positions[1].size() / 3 - a.levels.positions[0].size() / 3 < pc.size());  // level 1 under the density
  CHECK(a.control_choice.find("smoothed") == std::string::npos);
  CHECK(a.control_choice == b.control_choice);
  CHECK(a.levels.chunks == b.levels.chunks);
}

TEST_CASE("a noisy cloud: the level before the crossing one is smoothed too, closer to the truth in fewer bytes") {
  // Smoothing (displacement_smoothing.h) averages the crossing level's
  // displacements at kNeighbourWeight and, since the twelfth session, the
  // level before it at kBeforeCrossingWeight.  On this torus (8,000 points,
  // crossing at level 3) level 2 must come out closer to the true surface
  // and smaller than without smoothing; before, it was the same file.
  const test::Shape s = test::genus_shapes()[1];  // torus
  Scan scan = noisy_torus_scan(s);
  EncodeOptions o;
  o.levels = 3;
  auto on = encode_points(scan.points, o);
  o.smooth_noise = false;
  auto off = encode_points(scan.points, o);
  REQUIRE(on.ok());
  REQUIRE(off.ok());
  const Encoding& a = on.value();
  const Encoding& b = off.value();
  const size_t points = scan.points.size();
  REQUIRE(a.levels.positions[2].size() / 3 <= points);  // level 2 under the density,
  REQUIRE(a.levels.positions[3].size() / 3 - a.levels.positions[2].size() / 3 > points);  // level 3 crosses it
  const double error_on = level_error(a, 2, s, scan.truth), error_off = level_error(b, 2, s, scan.truth);
  INFO("level 2: " << prefix_bytes(a, 2) << " bytes, error " << error_on << " smoothed; " << prefix_bytes(b, 2) << " bytes, error "
                   << error_off << " as sampled");
  CHECK(error_on < error_off);
  CHECK(prefix_bytes(a, 2) < prefix_bytes(b, 2));
}

TEST_CASE("a noisy cloud's meta says the step its levels were rounded at, a clean one's says nothing new") {
  // A noisy cloud's levels round at a step from the points' noise
  // (levels.cpp kNoiseStep), coarser than the error target's; the header's
  // error target stays the one asked for, so meta `quantization` must name
  // the step the levels hold.  Before, nothing in the file said it.  (At
  // noise 1e-3 this torus's noise step is under the target's; at 2e-3 over.)
  const test::Shape s = test::genus_shapes()[1];  // torus
  const auto quantization = [](const Encoding& e) -> const std::string* {
    for (const auto& m : e.contents.metadata)
      if (m.key == "quantization") return &m.value;
    return nullptr;
  };
  EncodeOptions o;
  o.levels = 2;
  auto noisy = encode_points(noisy_torus_scan(s, 2e-3).points, o);
  REQUIRE(noisy.ok());
  const Encoding& a = noisy.value();
  REQUIRE(a.contents.levels.size() == 2);
  const float used = a.contents.levels[0].step;
  CHECK(a.contents.levels[1].step == used);
  REQUIRE(used > a.step);  // the premise: the noise's step is the coarser
  const std::string* note = quantization(a);
  REQUIRE(note != nullptr);
  INFO("quantization: " << *note << "; step " << used << ", the target's " << a.step);
  const size_t at = note->find("step ");
  REQUIRE(at != std::string::npos);
  const double said = std::strtod(note->c_str() + at + 5, nullptr);
  CHECK(std::abs(said - used) <= 1e-5 * used);
  CHECK(note->find("noise") != std::string::npos);
  CHECK(a.contents.header.error_target == static_cast<float>(o.error));  // the header: the target asked for

  auto clean = encode_points(scan_of(s, 8000).points, o);
  REQUIRE(clean.ok());
  for (const format::Level& l : clean.value().contents.levels) CHECK(l.step == clean.value().step);
  CHECK(quantization(clean.value()) == nullptr);
}
