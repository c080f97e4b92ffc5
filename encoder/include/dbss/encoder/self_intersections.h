// Triangles that cross each other: finding the pairs, and moving vertices
// until none are left.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "dbss/decoder/mesh.h"

namespace dbss {

// Pairs (f < g) of triangles that share no vertex yet intersect, sorted; a
// uniform grid of triangle bounds narrows the candidates.
std::vector<std::pair<uint32_t, uint32_t>> self_intersections(const TriangleMesh& m);
size_t count_self_intersections(const TriangleMesh& m);

// Where triangles cross, puts their vertices back at their positions in
// `safe` (the same mesh before some moves, without crossings), up to
// `rounds` times, then every vertex.  Returns how many vertex moves were
// undone.
size_t undo_self_intersections(TriangleMesh& m, const std::vector<float>& safe, int rounds = 8);
// The same, when `safe` is known to have no crossings (the state an undo
// left, which started from a mesh without any, such as the carved shell):
// a crossing pair then has a triangle with a corner moved since, and the
// first search tries only those.  The same pairs, at a fraction of a full
// search's cost when few vertices moved.  (undo_self_intersections does
// not assume it: given a `safe` that crosses, it ends at `safe`.)
size_t undo_new_crossings(TriangleMesh& m, const std::vector<float>& safe, int rounds = 8);

// Where triangles cross and no earlier state is at hand (after edge
// collapses), moves their vertices to their neighbours' mean (boundary
// vertices: their two boundary neighbours' mean), up to `rounds` times.
// Returns the number of vertex moves.
size_t relax_self_intersections(TriangleMesh& m, int rounds = 10);

}  // namespace dbss
