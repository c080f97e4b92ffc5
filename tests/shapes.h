// Meshes with known counts and genus, built in the tests.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

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

namespace dbss::test {

// Two apexes of valence n over an n-gon of valence-4 vertices: genus 0.
inline TriangleMesh bipyramid(uint32_t n, float height = 1.0f) {
  TriangleMesh m;
  for (uint32_t i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    m.positions.insert(m.positions.end(), {static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.0f});
  }
  m.positions.insert(m.positions.end(), {0, 0, height, 0, 0, -height});
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t j = (i + 1) % n;
    m.triangles.insert(m.triangles.end(), {i, j, n});
    m.triangles.insert(m.triangles.end(), {j, i, n + 1});
  }
  return m;
}

// Latitude-longitude sphere: `rings` circles of `sides` vertices plus two
// poles of valence `sides`; V = rings * sides + 2, genus 0.
inline TriangleMesh uv_sphere(uint32_t rings, uint32_t sides) {
  TriangleMesh m;
  for (uint32_t i = 0; i < rings; ++i) {
    const double t = std::numbers::pi * (i + 1) / (rings + 1);
    for (uint32_t j = 0; j < sides; ++j) {
      const double a = 2 * std::numbers::pi * j / sides;
      m.positions.insert(m.positions.end(), {static_cast<float>(std::sin(t) * std::cos(a)),
                                             static_cast<float>(std::sin(t) * std::sin(a)),
                                             static_cast<float>(std::cos(t))});
    }
  }
  const uint32_t north = rings * sides, south = north + 1;
  m.positions.insert(m.positions.end(), {0, 0, 1, 0, 0, -1});
  auto id = [&](uint32_t i, uint32_t j) { return i * sides + j % sides; };
  for (uint32_t j = 0; j < sides; ++j) {
    m.triangles.insert(m.triangles.end(), {north, id(0, j), id(0, j + 1)});
    m.triangles.insert(m.triangles.end(), {south, id(rings - 1, j + 1), id(rings - 1, j)});
    for (uint32_t i = 0; i + 1 < rings; ++i) {
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

inline TriangleMesh tetrahedron() {
  TriangleMesh m;
  m.positions = {1, 1, 1, -1, -1, 1, -1, 1, -1, 1, -1, -1};
  m.triangles = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};
  return m;
}

inline TriangleMesh icosahedron() {
  const float t = 1.6180339887f;
  TriangleMesh m;
  m.positions = {-1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, 0, 0, -1, t, 0, 1, t,
                 0, -1, -t, 0, 1, -t, t, 0, -1, t, 0, 1, -t, 0, -1, -t, 0, 1};
  m.triangles = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
                 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
  return m;
}

// A planar (z = 0) open grid of nx x ny quads split along alternating
// diagonals, so interior valences are 4, 6 and 8 and it has a boundary.
inline TriangleMesh planar_grid(uint32_t nx, uint32_t ny) {
  TriangleMesh m;
  for (uint32_t j = 0; j <= ny; ++j)
    for (uint32_t i = 0; i <= nx; ++i)
      m.positions.insert(m.positions.end(), {static_cast<float>(i) + 0.1f * static_cast<float>(j % 2), static_cast<float>(j), 0.0f});
  auto id = [&](uint32_t i, uint32_t j) { return j * (nx + 1) + i; };
  for (uint32_t j = 0; j < ny; ++j)
    for (uint32_t i = 0; i < nx; ++i) {
      if ((i + j) % 2 == 0) {
        m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j), id(i, j + 1)});
        m.triangles.insert(m.triangles.end(), {id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  return m;
}

// Moves every vertex by a fixed pseudo-random amount, so no symmetry hides
// a wrongly ordered stencil.
inline TriangleMesh jitter(TriangleMesh m, float amount, uint32_t seed = 1) {
  uint32_t s = seed * 2654435761u + 1;
  for (float& x : m.positions) {
    s = s * 1664525u + 1013904223u;
    x += amount * (static_cast<float>(s >> 8) / 16777216.0f - 0.5f);
  }
  return m;
}

// The mesh without every triangle that touches a vertex marked in `gone`
// (the vertices stay, unreferenced): holes cut where the stars were.
inline TriangleMesh without_stars(TriangleMesh m, const std::vector<uint8_t>& gone) {
  std::vector<uint32_t> kept;
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    const uint32_t* t = &m.triangles[3 * f];
    if (gone[t[0]] || gone[t[1]] || gone[t[2]]) continue;
    kept.insert(kept.end(), t, t + 3);
  }
  m.triangles = kept;
  return m;
}

}  // namespace dbss::test
