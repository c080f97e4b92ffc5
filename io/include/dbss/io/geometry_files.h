// Points and meshes in the common interchange formats: PLY, OBJ, OFF, STL,
// glTF (.glb, .gltf) and XYZ.  One file per format in io/src, each with its
// reader and writer, behind one table keyed by extension
// (io/src/formats.cpp): adding a format is one file and one row.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/format/status.h"

namespace dbss {

// Points in model units: the encoder's first stage struct.
struct PointCloud {
  std::vector<float> xyz;      // 3 per point
  std::vector<float> normals;  // 3 per point when the file has them, else empty
  size_t size() const noexcept { return xyz.size() / 3; }
};

// What a file holds: its vertices (with per-vertex normals when it has
// them) and, for a file with faces, its triangles (polygons split into fans
// from their first corner).  Empty `triangles`: a point set.
struct GeometryFile {
  PointCloud points;
  std::vector<uint32_t> triangles;
};

// Vertices and faces of PLY (`face` element, list `vertex_indices` or
// `vertex_index`), OBJ (`f` lines, negative indices relative, `v/vt/vn`
// forms), OFF and STL (corners merged where their coordinates are equal);
// XYZ has no faces.  Errors name the file and the line, byte or face: an
// index out of range, a face with fewer than 3 corners, and everything
// read_points() refuses.  glTF: the triangles (and strips, fans and points)
// of the default scene's meshes, placed by their nodes' transforms (in
// double, then rounded to float; untransformed positions are kept bit for
// bit), with vertices of equal position merged in first-use order, since
// glTF splits vertices at texture seams and between primitives.  Lines,
// sparse accessors and Draco-compressed primitives are refused; normals,
// texture coordinates, colours and materials are not read.
Result<GeometryFile> read_geometry(const std::string& path);
Result<GeometryFile> parse_geometry(const std::string& name, std::string_view bytes);

// A file's triangle mesh; invalid_argument naming the file when it has no
// faces.
Result<TriangleMesh> read_mesh(const std::string& path);

// Reads the vertices of PLY (ascii, binary little or big endian; float,
// double or integer coordinates; other properties and elements skipped), OBJ
// (`v` lines), OFF (with or without colours/normals, faces ignored), XYZ
// (`x y z` or `x y z nx ny nz` per line) and STL (ascii or binary; the
// triangle corners, duplicates merged) and glTF (as read_geometry()).  The
// format is chosen by extension, case-insensitive.  Errors (invalid_argument / io) name the file and the
// line or byte: unreadable, empty, malformed, cut short, NaN, infinite or
// over 1e15 in magnitude.
Result<PointCloud> read_points(const std::string& path);

// Same, from bytes already in memory; `name` is used in messages and its
// extension picks the format.
Result<PointCloud> parse_points(const std::string& name, std::string_view bytes);

// A triangle mesh as .obj, .off, binary little-endian .ply, binary .stl,
// .glb or .gltf (one mesh, see dbss/io/gltf.h), chosen by the extension of
// `path`; written atomically.  invalid_argument for another extension, and
// for glTF a mesh without triangles.
Status write_mesh(const std::string& path, const TriangleMesh& mesh);

// The extensions read_points() and write_mesh() accept, as ".ply, .obj, ..."
// for messages and --help.
std::string readable_extensions();
std::string writable_extensions();

}  // namespace dbss
