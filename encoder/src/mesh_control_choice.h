// Mesh input: a larger control mesh when the default one's last level is
// floor-bound.  Internal to the encoder (encode_mesh.cpp).
//
// Why (bench/lod_bench.md, "eighth session" and "ninth session"): one file
// serves every prefix, and a larger control mesh makes every prefix
// dearer, so on most meshes the default is best at every Draco qp.  But on
// meshes whose default control mesh cannot carry the detail the target
// asks for (cow, elephant, bull: their last level's error barely falls
// when the target halves), 1.5x the faces is cheaper at every qp.  The
// floor shows in one number the encoder can measure after the default
// encoding: the last level's two-sided error against the input over the
// error target.  Rounding alone leaves about a third of the target
// (bunny00, armadillo); well above it, what is left is what the levels
// cannot represent, which a finer step does not remove and a finer
// control mesh does.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "dbss/encoder/encode.h"
#include "dbss/encoder/mesh_input.h"
#include "dbss/format/status.h"

namespace dbss {

// Two-sided mean distance (model units) between a level and the input:
// from (a stride of at most kMeshChoiceProbe) the level's triangle
// centroids to the input surface, and from the input's triangle centroids
// to the level, each area-weighted.  Cheaper than the measuring library's
// area-uniform samples (which the encoder does not link) and close to it:
// the choice compares ratios of it, not its value against a bench's.
inline constexpr size_t kMeshChoiceProbe = size_t{1} << 13;
double level_distance_to_mesh(const std::vector<float>& positions, const std::vector<uint32_t>& triangles,
                              const MeshSurface& input_surface, const TriangleMesh& input);

// Encodes the input over a control mesh of `faces` triangles into `e`
// (control mesh, levels and the file, without control.choice), as
// encode_mesh does for the default.
using MeshControlEncoder = std::function<Status(uint32_t faces, Encoding& e, MeshControlStats& stats)>;

struct MeshControlChoiceOptions {
  double floor_ratio = 0;  // MeshEncodeOptions::floor_ratio
  double scale = 0;        // MeshEncodeOptions::larger_control
};

// `e` and `stats` hold the default encoding over `faces`.  When its last
// level's error over the target (e.error x diagonal) is at least
// floor_ratio, a candidate over scale x faces is encoded and replaces the
// default when its levels reach the default's last level's error (within
// kRdTolerance) in fewer prefix bytes (log-log between its levels, as the
// points path's rd_curve_dominates).  Sets e.control_choice (why) and
// e.seconds.choice (what the choice added).  A candidate that fails to
// encode is no candidate: the default stands.
void choose_mesh_control(Encoding& e, MeshControlStats& stats, uint32_t faces, const TriangleMesh& input,
                         const MeshSurface& surface, const MeshControlEncoder& encode, const MeshControlChoiceOptions& o);

}  // namespace dbss
