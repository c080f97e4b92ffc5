// Writing meshes for inspection (stage dumps, decoded levels).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/cell_carving.h"
#include "dbss/format/status.h"

namespace dbss {

// Wavefront OBJ of a triangle mesh, written atomically.
Status write_obj(const std::string& path, const TriangleMesh& mesh);

// A triangle mesh as .obj, .off, binary little-endian .ply or binary .stl,
// chosen by the extension of `path`; written atomically.  invalid_argument
// for another extension.
Status write_mesh(const std::string& path, const TriangleMesh& mesh);

// The outer faces of a set of cells as an OBJ quad mesh: `which` picks the
// cells (e.g. occupied ones, or all solid ones after carving).
Status write_cells_obj(const std::string& path, const CellGrid& grid, bool occupied_only);

}  // namespace dbss
