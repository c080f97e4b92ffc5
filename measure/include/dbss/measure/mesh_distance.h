// Two-sided distance between two triangle meshes' surfaces, for errors
// against a known true surface (bench/rd_bench).  Unlike
// surface_distance.h, which measures against points and so has a floor of
// about half their spacing, both directions here are exact distances to a
// surface: identical meshes measure 0.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/triangle_tree.h"

namespace dbss {

struct MeshDistanceOptions {
  size_t samples = 200000;  // in all: half on each surface, area-uniform
  uint32_t seed = 1;        // of the samples; a fixed seed gives the same figure on every run
  unsigned threads = 1;     // for the distance queries; the result is the same for any count
};

// Model units.  `a_to_b`: from samples of a's surface to b's surface, and
// the other way round.  A mesh without triangles is infinitely far.
struct MeshDistance {
  double a_to_b_mean = 0, a_to_b_max = 0;
  double b_to_a_mean = 0, b_to_a_max = 0;
  double mean() const noexcept { return 0.5 * (a_to_b_mean + b_to_a_mean); }
  // The largest sampled distance: a lower bound of the Hausdorff distance
  // that approaches it as samples grow.
  double max() const noexcept { return a_to_b_max > b_to_a_max ? a_to_b_max : b_to_a_max; }
};

MeshDistance mesh_distance(const TriangleMesh& a, const TriangleMesh& b, const MeshDistanceOptions& options = {});

// mesh_distance(a, b, options) for many meshes a against one b, with b's
// triangle tree and b's samples made once: measuring every level of an
// encoding against a million-triangle input rebuilt the input's tree per
// level (issue 18: `dbss encode`'s report on an 832k-triangle armadillo,
// 1-5 s of CPU out of 17-25).  Gives the same figures as mesh_distance,
// bit for bit; holds b's tree (about 100 bytes a triangle) meanwhile.
class MeshDistanceTo {
 public:
  MeshDistanceTo(const TriangleMesh& b, const MeshDistanceOptions& options = {});
  MeshDistance from(const TriangleMesh& a) const;

 private:
  MeshDistanceOptions options_;
  size_t b_triangles_ = 0;
  TriangleTree tree_;             // of b
  std::vector<double> samples_;  // of b's surface, for b -> a
};

}  // namespace dbss
