// The table of geometry formats: each row names a format's extensions and
// its reader and writer (io/src/<format>.cpp).
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "dbss/io/geometry_files.h"

namespace dbss::io_detail {

using GeometryReader = Result<GeometryFile> (*)(const std::string& name, std::string_view bytes);
// The whole file's bytes for a mesh, or why it cannot be written.
using MeshWriter = Result<std::string> (*)(const TriangleMesh& mesh);

struct GeometryFormat {
  std::string_view extensions[3];  // lower case, without the dot; unused ones empty
  GeometryReader read;             // null: cannot be read
  MeshWriter write_mesh;           // null: cannot be written
};

std::span<const GeometryFormat> geometry_formats();
// The row for a lower-case extension, or null.
const GeometryFormat* find_format(std::string_view extension);

Result<GeometryFile> parse_ply(const std::string& name, std::string_view bytes);
Result<GeometryFile> parse_obj(const std::string& name, std::string_view text);
Result<GeometryFile> parse_off(const std::string& name, std::string_view text);
Result<GeometryFile> parse_stl(const std::string& name, std::string_view bytes);
Result<GeometryFile> parse_xyz(const std::string& name, std::string_view text);
Result<GeometryFile> parse_gltf(const std::string& name, std::string_view bytes);
Result<std::string> write_ply(const TriangleMesh& mesh);
Result<std::string> write_obj(const TriangleMesh& mesh);
Result<std::string> write_off(const TriangleMesh& mesh);
Result<std::string> write_stl(const TriangleMesh& mesh);
Result<std::string> write_glb(const TriangleMesh& mesh);
Result<std::string> write_gltf(const TriangleMesh& mesh);

}  // namespace dbss::io_detail
