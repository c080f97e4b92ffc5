// A level's sampled displacements averaged with their neighbours' (noisy
// clouds, point path).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace dbss {

// With EncodeOptions::smooth_noise, on a noisy cloud (points_are_noisy),
// levels from this one on code the smoothed displacements.
inline constexpr uint32_t kSmoothFromLevel = 2;
// The neighbours' share of a smoothed displacement.
inline constexpr double kNeighbourWeight = 0.8;

// `refined`: the level's triangles (odd vertex e is vertex `even` + e);
// `d`: each odd vertex's sampled displacement, `ok`: whether it may take
// part (a clamped or unsampled one neither gives nor takes).  Returns
// (1 - w) d_e + w * (the mean of d over the odd vertices sharing an edge
// with e), d_e itself for a vertex with no such neighbour.  Why: on a noisy
// cloud each sample is the local fit's height, off the true surface by the
// fit's own error, which differs from one odd vertex to the next.  Linear
// interpolation inside a level's triangles averages those errors; the
// butterfly, once the levels past the points store zeros, interpolates the
// vertices with a smooth surface that keeps their full error, so the error
// rose 3-4% past the last coded level (noisy torus, 8,000 points, noise 1e-3
// of the diagonal).  Averaged with their neighbours the samples' errors
// vary smoothly and are smaller.  Measured there (seeds 1-2): the floor
// -5.6%, 6% fewer bytes, the rise into the first zero level 3.5-3.7% ->
// 2.4-2.6%.  Not the default: on the noisy eight (rd_bench, noise 2e-3)
// the control choice then keeps the default mesh, and the file is 30% larger
// for a 3% higher floor.  A neighbour's displacement is measured along its own normal
// from its own predicted point: on a smooth level the two differ by far
// less than the noise.
std::vector<double> smooth_displacements(std::span<const uint32_t> refined, size_t even, std::span<const double> d,
                                         std::span<const uint8_t> ok, double w);

}  // namespace dbss
