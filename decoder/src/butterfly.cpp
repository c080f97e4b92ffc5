#include "butterfly.h"

#include "butterfly_terms.h"

namespace dbss {

namespace {

// Appends one stencil's terms to the generic tables.
struct Builder {
  Stencils& s;
  void add(uint32_t v, double w) {
    s.other_index.push_back(v);
    s.other_weight.push_back(w);
  }
};

using detail::kRegularWeights;

}  // namespace

Stencils build_stencils(const LevelTopology& lt, bool all_generic) {
  const detail::TopologyRef t = detail::ref_of(lt);
  Stencils s;
  const uint32_t edges = t.edge_count;
  s.odd_count = edges;
  s.regular_odd.resize(edges);
  s.regular_index.resize(size_t{edges} * 8);
  s.other_offset.push_back(0);
  Builder b{s};
  uint32_t regular = 0;
  for (uint32_t e = 0; e < edges; ++e) {
    const uint32_t h = lt.edge_half[e], o = t.twin[h];
    if (!all_generic && o != kNoHalfEdge && detail::regular_end(t, t.tri[h]) &&
        detail::regular_end(t, t.tri[next_half(h)])) {
      detail::regular_vertices(t, h, o, &s.regular_index[8 * size_t{regular}]);
      s.regular_odd[regular++] = e;
      continue;
    }
    s.other_odd.push_back(e);
    detail::edge_terms(t, h, b);
    s.other_offset.push_back(static_cast<uint32_t>(s.other_index.size()));
  }
  s.regular_odd.resize(regular);
  s.regular_index.resize(size_t{regular} * 8);
  return s;
}

void stencil_terms(const Stencils& s, uint32_t odd, std::vector<uint32_t>& index, std::vector<double>& weight) {
  index.clear();
  weight.clear();
  for (size_t i = 0; i < s.regular_odd.size(); ++i)
    if (s.regular_odd[i] == odd) {
      index.assign(&s.regular_index[8 * i], &s.regular_index[8 * i + 8]);
      weight.assign(kRegularWeights, kRegularWeights + 8);
      return;
    }
  for (size_t i = 0; i < s.other_odd.size(); ++i)
    if (s.other_odd[i] == odd) {
      index.assign(&s.other_index[s.other_offset[i]], &s.other_index[s.other_offset[i + 1]]);
      weight.assign(&s.other_weight[s.other_offset[i]], &s.other_weight[s.other_offset[i + 1]]);
      return;
    }
}

void apply_stencils(const Stencils& s, const float* p, uint32_t rb, uint32_t re, uint32_t ob, uint32_t oe, float* odd) {
  // Regular stencils: the same ordered sum as the generic loop below with
  // kRegular's weights, written out so the compiler keeps it in registers.
  const uint32_t* ri = s.regular_index.data();
  for (uint32_t i = rb; i < re; ++i) {
    const uint32_t* r = ri + 8 * size_t{i};
    float* out = odd + 3 * size_t{s.regular_odd[i]};
    for (int k = 0; k < 3; ++k) {
      double a = 0;
      a = a + 0.5 * p[3 * size_t{r[0]} + k];
      a = a + 0.5 * p[3 * size_t{r[1]} + k];
      a = a + 0.125 * p[3 * size_t{r[2]} + k];
      a = a + 0.125 * p[3 * size_t{r[3]} + k];
      a = a + -0.0625 * p[3 * size_t{r[4]} + k];
      a = a + -0.0625 * p[3 * size_t{r[5]} + k];
      a = a + -0.0625 * p[3 * size_t{r[6]} + k];
      a = a + -0.0625 * p[3 * size_t{r[7]} + k];
      out[k] = static_cast<float>(a);
    }
  }
  const uint32_t* off = s.other_offset.data();
  const uint32_t* idx = s.other_index.data();
  const double* wt = s.other_weight.data();
  for (uint32_t e = ob; e < oe; ++e) {
    double x = 0, y = 0, z = 0;
    for (uint32_t i = off[e]; i < off[e + 1]; ++i) {
      const float* q = p + 3 * size_t{idx[i]};
      const double w = wt[i];
      x = x + w * q[0];
      y = y + w * q[1];
      z = z + w * q[2];
    }
    float* out = odd + 3 * size_t{s.other_odd[e]};
    out[0] = static_cast<float>(x);
    out[1] = static_cast<float>(y);
    out[2] = static_cast<float>(z);
  }
}

}  // namespace dbss
