// Random points on a triangle mesh's surface, area-uniform, from a fixed
// seed.  The rate-distortion benchmark draws its input points from a true
// mesh with it, and the mesh-to-mesh distance its probe points.  Every
// number comes from std::mt19937's raw output through explicit arithmetic
// (no std::*_distribution, whose results differ between standard
// libraries), so a seed gives the same points on every platform.
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "dbss/decoder/mesh.h"

namespace dbss {

// Uniform in [0, 1) with 53 random bits: two draws of the generator.
double uniform01(std::mt19937& rng);
// Standard normal (Box-Muller on uniform01).
double standard_normal(std::mt19937& rng);

// `count` points (x, y, z each) on the surface of `mesh`, each triangle hit
// in proportion to its area.  Empty for a mesh without area.
std::vector<double> sample_surface(const TriangleMesh& mesh, size_t count, uint32_t seed);

}  // namespace dbss
