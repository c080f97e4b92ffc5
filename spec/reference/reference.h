// dbss_ref: a reference decoder for .dbss files, written from
// spec/dbss-format.md and spec/decoding.md alone.
//
// It shares no code with the project's reader and decoder, so tests that
// compare the two (tests/reference/) witness the golden files twice. It is
// written to be read next to the spec, not to be fast: every function says
// which section it implements.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace dbss_ref {

// A triangle mesh: x y z per vertex, three corners per triangle.
struct Mesh {
  std::vector<float> positions;
  std::vector<uint32_t> triangles;
  // Version 1.1 (decoding.md section 3): 1 per crease edge in the canonical
  // edge order, 1 per corner vertex; both empty when the mesh has none.
  std::vector<uint8_t> crease;
  std::vector<uint8_t> corner;
};

struct Decoded {
  // The spec's error code name (dbss-format.md section 13), empty if the
  // whole file was read.
  std::string error;
  // Levels 0..l that were verified before any error (section 11: a reader
  // keeps every chunk it verified before the failure).
  std::vector<Mesh> levels;
};

// Reads a whole file: the container checks of dbss-format.md section 12,
// the control mesh (decoding.md section 2) and every level (sections 3-7).
Decoded decode(std::span<const uint8_t> file);

// One refinement step of decoding.md sections 3-7 on any oriented manifold
// triangle mesh (with or without boundary, valences up to 64). `q` holds one
// integer per edge of `level` in the canonical edge order, displaced by
// q * step along the odd vertex's normal; an empty `q` means no displacement
// at all (the undisplaced stencil points are returned as they are).
// Throws std::invalid_argument for a mesh the spec does not define a
// refinement for. With `normals`, also returns every odd vertex's binary64
// unit normal of section 6 (3 per odd vertex, in edge order), with or
// without displacement.
//
// Version 1.3 (decoding.md section 7a): `boundary` holds one integer per
// boundary edge of `level` in canonical edge order (empty: none), moved by
// boundary * boundary_step across the boundary after the normal
// displacement; only with a non-empty `q`.
Mesh subdivide(const Mesh& level, std::span<const int32_t> q, float step,
               std::vector<double>* normals = nullptr, std::span<const int32_t> boundary = {},
               float boundary_step = 0);

namespace detail {
// decoding.md section 2 step 6: no crease edge on the boundary (true
// without creases).
bool creases_fit(const Mesh& mesh);
}  // namespace detail

// decoding.md section 8: FNV-1a 64 over the little-endian binary32 bytes of
// the positions, vertex by vertex, x y z.
uint64_t fnv1a64(const Mesh& mesh);

// dbss-format.md section 5, exposed for tests.
uint32_t crc32c(std::span<const uint8_t> bytes);

}  // namespace dbss_ref
