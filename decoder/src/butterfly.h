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

#include "butterfly_weight.h"
#include "dbss/decoder/topology.h"

namespace dbss {

struct Stencils {
  uint32_t odd_count = 0;
  // Most edges of a refined level are regular (both ends interior with
  // valence 6): their stencil is fixed, so only the 8 vertices are stored,
  // in the order u, w, c, d, then the wings across w-c, c-u, u-d, d-w.
  std::vector<uint32_t> regular_odd;    // odd vertex (edge) of each regular stencil
  std::vector<uint32_t> regular_index;  // 8 per regular stencil
  // Every other edge: odd vertex other_odd[i] = sum over
  // j in [other_offset[i], other_offset[i+1]) of other_weight[j] * p[other_index[j]].
  std::vector<uint32_t> other_odd;
  std::vector<uint32_t> other_offset;
  std::vector<uint32_t> other_index;
  std::vector<double> other_weight;
  uint32_t size() const noexcept { return odd_count; }
};

// The stencil of every edge of `t`.  With `all_generic`, regular edges are
// stored as weighted lists too (for tests: both forms must agree bit for bit).
Stencils build_stencils(const LevelTopology& t, bool all_generic = false);

// One stencil as the ordered (vertex, weight) list the spec defines.
void stencil_terms(const Stencils& s, uint32_t odd, std::vector<uint32_t>& index, std::vector<double>& weight);

// Evaluates regular stencils [rb, re) and other stencils [ob, oe), writing
// odd vertex e's 3 floats to odd[3 * e].
void apply_stencils(const Stencils& s, const float* positions, uint32_t rb, uint32_t re, uint32_t ob, uint32_t oe,
                    float* odd);

}  // namespace dbss
