// Two-sided distance between two triangle meshes' surfaces, for errors
// against a known true surface (bench/rd_bench).  Unlike
// surface_distance.h, which measures against points and so has a floor of
// about half their spacing, both directions here are exact distances to a
// surface: identical meshes measure 0.
#pragma once

#include <cstddef>
#include <cstdint>

#include "dbss/decoder/mesh.h"

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

}  // namespace dbss
