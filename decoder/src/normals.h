// Unit normals at the odd vertices of a freshly subdivided level, from the
// undisplaced positions (spec/decoding.md, "Normals").
#pragma once

#include <cstdint>
#include <vector>

#include "dbss/decoder/topology.h"

namespace dbss {

// Per odd vertex of the next level, its neighbours there in counter-clockwise
// order, 6 entries each: for the edge u->w of triangle (u, w, c) with twin in
// (w, u, d) and m_xy the odd vertex on edge x-y,
//   interior: m_cu, u, m_ud, m_dw, w, m_wc
//   boundary: w, m_wc, m_cu, u, kNoHalfEdge, kNoHalfEdge
std::vector<uint32_t> build_odd_rings(const LevelTopology& t);

// normal = sum over consecutive ring pairs (closed for 6, open for 4) of
// (r_i - m) x (r_{i+1} - m) in binary64, times 1 / its length; zero when the
// length is zero.  Writes 3 doubles per odd vertex e in [begin, end).
void odd_normals(const uint32_t* rings, const float* positions, uint32_t first_odd, uint32_t begin, uint32_t end,
                 double* normals);

}  // namespace dbss
