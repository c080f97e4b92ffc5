// The encoder's hook into a refinement step (see level_refiner.h): its own
// header so the decoder's internals can take one without the public
// LevelRefiner class.
#pragma once

#include <cstdint>
#include <functional>

namespace dbss {

// Chooses odd vertex `odd`'s integer q: `point` is its undisplaced stencil
// point and `normal` its unit normal (zero when degenerate), both in
// binary64 as the decoder holds them; u and w are its edge's two ends in
// the level being refined (3 floats each).  Called from several threads at
// once for different odd vertices, so it must be safe to call concurrently;
// the vertex then moves by q * step along the normal.
using OddChooser = std::function<int32_t(uint32_t odd, const double point[3], const double normal[3],
                                         const float* u, const float* w)>;

}  // namespace dbss

namespace dbss {

// Format 1.3 (spec/decoding.md section 7a): chooses the k-th boundary odd
// vertex's in-surface integer (`odd` is its odd-vertex number).  `m` is its
// binary32 position after the normal displacement, `b` its unit direction
// across the boundary (t x n normalized; zero when degenerate), `n` its unit
// normal, u and w its edge's ends.  Called in boundary-edge order from one
// thread; the vertex then moves by the integer * step along b.
using BoundaryChooser = std::function<int32_t(uint32_t k, uint32_t odd, const float m[3], const double b[3],
                                              const double n[3], const float* u, const float* w)>;

}  // namespace dbss
