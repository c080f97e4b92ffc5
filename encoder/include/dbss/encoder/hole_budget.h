// The control mesh's faces for a mesh with holes, per hole (issue 18): a
// hole's boundary loop gets the control vertices its curve needs, and the
// control mesh the faces those vertices take, on top of the closed
// budget.
#pragma once

#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"

namespace dbss {

// How many of a closed polyline's vertices a polygon needs so that every
// vertex is within `tolerance` of it (Douglas-Peucker from the loop's two
// mutually farthest vertices), at least 3.
uint32_t loop_vertices_needed(const std::vector<float>& positions, const std::vector<uint32_t>& loop, double tolerance);

struct HoleBudget {
  uint32_t faces = 0;                  // the control mesh's target
  uint32_t closed_faces = 0;           // default_control_faces of the input
  double edge_length = 0;              // of an equilateral triangle of the closed budget on the input's area
  std::vector<uint32_t> loop_vertices; // per loop, loop_vertices_needed at kHoleTolerance x edge_length
};

// A control vertex on a loop stays within this many of the closed budget's
// edge lengths of the input's boundary curve.  0.25 was measured too
// (bench/lod_bench.md, "Issue 18, fifth session"): on elephant-with-holes
// 0.125 gave 1.72x Draco at qp10's error against 1.98x.
inline constexpr double kHoleTolerance = 0.125;
// Faces per control vertex a loop needs: one for the vertex on the rim
// (a rim vertex adds one face, an interior one two) and two for a ring of
// as many interior vertices round the hole, so the faces next to a hole
// are as fine as its rim.  Measured against 1.5 and 2 (the same section).
inline constexpr double kHoleFacesPerVertex = 3.0;

// The control mesh's faces for `mesh` (prepared, genus `genus`):
// default_control_faces plus, per boundary loop, kHoleFacesPerVertex x its
// loop_vertices_needed + 2 (cutting a hole of n rim vertices into a
// triangulated surface adds n + 2 faces).  A closed mesh gets
// default_control_faces, unchanged.  Even, at most UINT32_MAX - 1.
// (`tolerance` and `faces_per_vertex` for measuring other values.)
HoleBudget hole_budget(const TriangleMesh& mesh, int64_t genus, double tolerance = kHoleTolerance,
                       double faces_per_vertex = kHoleFacesPerVertex);

}  // namespace dbss
