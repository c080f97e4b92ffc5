// The format table and the dispatch by extension.
#include "formats.h"

#include <utility>

#include "dbss/io/file.h"
#include "text.h"

namespace dbss {

namespace io_detail {

namespace {
// Binary little-endian PLY first: the smallest of the mesh formats.
constexpr GeometryFormat kFormats[] = {
    {{"ply"}, parse_ply, write_ply},
    {{"obj"}, parse_obj, write_obj},
    {{"off"}, parse_off, write_off},
    {{"stl"}, parse_stl, write_stl},
    {{"glb"}, parse_gltf, write_glb},
    {{"gltf"}, parse_gltf, write_gltf},
    {{"xyz", "pts", "txt"}, parse_xyz, nullptr},
};

std::string list(bool readable) {
  std::string out;
  for (const GeometryFormat& f : kFormats) {
    if (!(readable ? f.read != nullptr : f.write_mesh != nullptr)) continue;
    // The first extension names the format; the others are aliases.
    out += (out.empty() ? "." : ", .") + std::string(f.extensions[0]);
  }
  return out;
}
}  // namespace

std::span<const GeometryFormat> geometry_formats() { return kFormats; }

const GeometryFormat* find_format(std::string_view extension) {
  for (const GeometryFormat& f : kFormats)
    for (std::string_view e : f.extensions)
      if (!e.empty() && e == extension) return &f;
  return nullptr;
}

}  // namespace io_detail

using namespace io_detail;

std::string readable_extensions() { return list(true); }
std::string writable_extensions() { return list(false); }

Result<GeometryFile> parse_geometry(const std::string& name, std::string_view bytes) {
  const std::string ext = lower_extension(name);
  const GeometryFormat* f = find_format(ext);
  if (f == nullptr || f->read == nullptr)
    return bad(name, "unknown input format '." + ext + "' (expected " + readable_extensions() + ")");
  Result<GeometryFile> r = f->read(name, bytes);
  if (r.ok() && r.value().points.size() == 0) return bad(name, "the file holds no points");
  return r;
}

Result<GeometryFile> read_geometry(const std::string& path) {
  // The format first: a device or a file of another kind is refused before
  // anything is read.
  const std::string ext = lower_extension(path);
  const GeometryFormat* f = find_format(ext);
  if (f == nullptr || f->read == nullptr)
    return bad(path, ext.empty() ? "no file extension to tell the format (expected " + readable_extensions() + ")"
                                 : "unknown input format '." + ext + "' (expected " + readable_extensions() + ")");
  // 4 GiB: over 100 million points in any of the formats, far beyond what
  // reconstruction handles on one machine.
  auto bytes = io::read_file(path, uint64_t{1} << 32);
  if (!bytes.ok()) return bytes.status();
  const std::vector<uint8_t>& b = bytes.value();
  return parse_geometry(path, std::string_view(reinterpret_cast<const char*>(b.data()), b.size()));
}

Result<PointCloud> parse_points(const std::string& name, std::string_view bytes) {
  auto g = parse_geometry(name, bytes);
  if (!g.ok()) return g.status();
  return std::move(g.value().points);
}

Result<PointCloud> read_points(const std::string& path) {
  auto g = read_geometry(path);
  if (!g.ok()) return g.status();
  return std::move(g.value().points);
}

Result<TriangleMesh> read_mesh(const std::string& path) {
  auto g = read_geometry(path);
  if (!g.ok()) return g.status();
  if (g.value().triangles.empty()) return bad(path, "the file has no faces: a point set, not a mesh");
  return TriangleMesh{std::move(g.value().points.xyz), std::move(g.value().triangles)};
}

Status write_mesh(const std::string& path, const TriangleMesh& mesh) {
  const GeometryFormat* f = find_format(lower_extension(path));
  if (f == nullptr || f->write_mesh == nullptr)
    return Status(ErrorCode::invalid_argument, path + ": unknown mesh format (expected " + writable_extensions() + ")");
  auto made = f->write_mesh(mesh);
  if (!made.ok()) return Status(made.status().code(), path + ": " + made.status().message());
  const std::string& bytes = made.value();
  return io::write_file_atomic(path, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
}

}  // namespace dbss
