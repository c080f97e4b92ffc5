// Edge ids of a level's half-edges in the canonical order (spec/decoding.md
// section 3): the first half-edge to reach an edge numbers it, so level
// l+1's odd vertex of edge e is vertex V_l + e.  Shared by zero_probe and
// adaptive_probe, which cost each level's values per edge.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

inline std::vector<uint32_t> half_edge_edges(const std::vector<uint32_t>& T) {
  std::unordered_map<uint64_t, uint32_t> seen;
  seen.reserve(T.size());
  std::vector<uint32_t> id(T.size());
  uint32_t next = 0;
  for (size_t h = 0; h < T.size(); ++h) {
    const uint32_t a = T[h], b = T[h % 3 == 2 ? h - 2 : h + 1];
    const uint64_t key = uint64_t{std::min(a, b)} << 32 | std::max(a, b);
    auto [it, fresh] = seen.emplace(key, next);
    if (fresh) ++next;
    id[h] = it->second;
  }
  return id;
}
