// A level's sampled displacements averaged with their neighbours' (noisy
// clouds, point path).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace dbss {

// With EncodeOptions::smooth_noise, on a noisy cloud (points_are_noisy),
// the level that crosses the points' density (the last that stores
// anything: dead_zone_steps) codes the smoothed displacements; the levels
// before it code their samples as they are.  Measured (bench/rd_bench.md,
// eleventh session): smoothing every level from level 2 on cost the noisy
// bunny00 (rd_bench, noise 2e-3) 9% at level 2 and the eight 20%; on the
// crossing level alone levels 0 to the one before it are unchanged, and
// the rise after it falls (eight 1.022-1.025 -> 1.016-1.018, noisy torus
// 1.030-1.037 -> 1.023-1.030) with 17-22% fewer bytes.
// The neighbours' share of a smoothed displacement (1.0 measured no better
// on the noisy torus).
inline constexpr double kNeighbourWeight = 0.8;

// The neighbours' share on the level before the crossing one (twelfth
// session, noise 2e-3 of the diagonal, rd_bench seed 1): the eight's level
// 3 came out in 13% fewer bytes and 2.5% closer to the truth, its floor
// 3.8% closer (6.05 -> 5.82e-4) and its worst rise 1.018 -> 1.014; the
// noisy torus of level_rise_probe (8,000 points, 1e-3, seeds 1-3) 4.8%
// closer at its floor, worst rise 1.034 -> 1.031.  Only where the file
// reaches the crossing level: one that stops before it is not smoothed
// (encode.cpp encodes the kept control mesh again only then).
inline constexpr double kBeforeCrossingWeight = 0.5;

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
// 2.4-2.6% (smoothing from level 2 on).  The control mesh is chosen without
// it (encode.cpp): with it, the noisy eight kept the default mesh and its
// file grew 30%.  A neighbour's displacement is measured along its own normal
// from its own predicted point: on a smooth level the two differ by far
// less than the noise.
std::vector<double> smooth_displacements(std::span<const uint32_t> refined, size_t even, std::span<const double> d,
                                         std::span<const uint8_t> ok, double w);

}  // namespace dbss
