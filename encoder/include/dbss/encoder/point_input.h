// Reading unorganized points from scan and mesh files.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "dbss/format/status.h"

namespace dbss {

// The encoder's first stage struct: points in model units.
struct PointCloud {
  std::vector<float> xyz;      // 3 per point
  std::vector<float> normals;  // 3 per point when the file has them, else empty
  size_t size() const noexcept { return xyz.size() / 3; }
};

// Reads the vertices of PLY (ascii, binary little or big endian; float,
// double or integer coordinates; other properties and elements skipped), OBJ
// (`v` lines), OFF (with or without colours/normals, faces ignored), XYZ
// (`x y z` or `x y z nx ny nz` per line) and STL (ascii or binary; the
// triangle corners, duplicates merged).  The format is chosen by extension,
// case-insensitive.  Errors (invalid_argument / io) name the file and the
// line or byte: unreadable, empty, malformed, cut short, NaN, infinite or
// over 1e15 in magnitude.
Result<PointCloud> read_points(const std::string& path);

// Same, from bytes already in memory; `name` is used in messages and its
// extension picks the format.
Result<PointCloud> parse_points(const std::string& name, std::string_view bytes);

// Checks a cloud is usable for reconstruction: at least 4 points not all on
// one plane.  The message names `name`.
Status check_reconstructible(const PointCloud& cloud, const std::string& name);

}  // namespace dbss
