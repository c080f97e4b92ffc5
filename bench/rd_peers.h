// The peers of the rate-distortion benchmark: surfaces reconstructed from
// the same points by CGAL, which Draco then compresses.  Benchmark-only: no
// library of the project depends on CGAL.
#pragma once

#include <string>
#include <vector>

#include "dbss/decoder/mesh.h"

namespace dbss::bench {

struct Reconstruction {
  TriangleMesh mesh;    // empty when the method failed
  std::string failure;  // why, when it did
  double seconds = 0;
};

// Advancing front surface reconstruction (CGAL's default radius ratio bound
// and beta) on points given as x, y, z triples.
Reconstruction advancing_front(const std::vector<double>& xyz);

// Poisson reconstruction as CGAL's poisson_surface_reconstruction_delaunay
// runs it with its documented defaults, on normals estimated from the points
// alone (jet fitting over `neighbours` points, oriented along a minimum
// spanning tree; points it cannot orient are dropped), since dbss gets no
// normals either.
Reconstruction poisson(const std::vector<double>& xyz, unsigned neighbours = 18);

}  // namespace dbss::bench
