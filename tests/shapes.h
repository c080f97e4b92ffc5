// Meshes with known counts and genus, built in the tests.
#pragma once

#include <cmath>
#include <numbers>

#include "dbss/decoder/mesh.h"

namespace dbss::test {

// A torus of rings x sides quads split into two triangles each: genus 1,
// V = rings * sides, E = 3V, F = 2V.
inline TriangleMesh torus(uint32_t rings, uint32_t sides, float major = 1.0f, float minor = 0.4f) {
  TriangleMesh m;
  for (uint32_t i = 0; i < rings; ++i)
    for (uint32_t j = 0; j < sides; ++j) {
      const double u = 2 * std::numbers::pi * i / rings, v = 2 * std::numbers::pi * j / sides;
      m.positions.push_back(static_cast<float>((major + minor * std::cos(v)) * std::cos(u)));
      m.positions.push_back(static_cast<float>((major + minor * std::cos(v)) * std::sin(u)));
      m.positions.push_back(static_cast<float>(minor * std::sin(v)));
    }
  auto id = [&](uint32_t i, uint32_t j) { return (i % rings) * sides + (j % sides); };
  for (uint32_t i = 0; i < rings; ++i)
    for (uint32_t j = 0; j < sides; ++j) {
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

}  // namespace dbss::test
