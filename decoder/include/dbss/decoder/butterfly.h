// Modified Butterfly stencils (Zorin, Schröder, Sweldens 1996) as flat
// tables, and their evaluation.
//
// build_stencils() is the topology pass: for every edge of a level, in edge
// order, the ordered list of (vertex, weight) whose sum is the edge's odd
// vertex.  apply_stencils() is the geometry pass: a flat loop that sums each
// list in order in binary64 and rounds once to binary32, so results are
// identical on every conforming compiler (spec/decoding.md).
#pragma once

#include <cstdint>
#include <vector>

#include "dbss/decoder/topology.h"

namespace dbss {

struct Stencils {
  // Odd vertex e = sum over i in [offset[e], offset[e+1]) of weight[i] * p[index[i]].
  std::vector<uint32_t> offset;
  std::vector<uint32_t> index;
  std::vector<double> weight;
  uint32_t size() const noexcept { return offset.empty() ? 0 : static_cast<uint32_t>(offset.size() - 1); }
};

// s_j of the extraordinary rule for valence k in 3..kMaxValence, j in 0..k-1:
// the binary64 value nearest to (1/4 + cos(2πj/k) + cos(4πj/k)/2) / k
// (k = 3: 5/12, -1/12, -1/12; k = 4: 3/8, 0, -1/8, 0).
double butterfly_weight(uint32_t k, uint32_t j) noexcept;

// The stencil of every edge of `t`.
Stencils build_stencils(const LevelTopology& t);

// Writes odd vertex e (3 floats) to odd[3 * (e - begin)] for e in [begin, end).
void apply_stencils(const Stencils& s, const float* positions, uint32_t begin, uint32_t end, float* odd);

}  // namespace dbss
