// Handles of a closed surface that run only through area the scan never
// saw: the tunnel a carving bores where a scanner left a gap on both faces
// of a thin part (no points on a wall between them), against a real
// through-hole, whose wall is scanned.
#pragma once

#include <cstdint>
#include <vector>

#include "dbss/encoder/point_index.h"
#include "dbss/encoder/point_input.h"

namespace dbss {

// Per vertex of `m`: its distance to the nearest point over the spacing of
// the points around it (the median nearest-neighbour distance of its
// kLocalPoints nearest points): how many of the local spacings separate the
// surface there from the scan.  The spacing is local because scans (and
// the bench's sampled shapes) vary in density several times over one
// shape: a sparse stretch's gaps are wide in median spacings but not in
// its own.
// `own` (may be null): points where the encoder built surface itself (its
// joined and bridged tubes); a vertex near them, in the same local
// spacings, counts as supported, so those tubes' handles are never bare
// while a bare handle elsewhere still is.
std::vector<float> bare_ratios(const TriangleMesh& m, const PointIndex& index, const PointIndex* own = nullptr);

// The handles of closed mesh `m` that run only through bare triangles
// (every vertex's ratio above `reach`): its genus minus that of the
// triangles left (bow-tie vertices split, boundaries counted as holes).
// `bare_vertices` (may be null) gets one vertex of each bare region that
// carries such a handle, for naming where it is.
uint32_t bare_handles(const TriangleMesh& m, const std::vector<float>& ratios, float reach,
                      std::vector<uint32_t>* bare_vertices = nullptr);

// bare_handles at each of `reaches` (the mesh's edges paired once).
std::vector<uint32_t> bare_handles_at(const TriangleMesh& m, const std::vector<float>& ratios, const std::vector<float>& reaches);

}  // namespace dbss
