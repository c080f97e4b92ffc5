// Container round trip, the README's main job until the encoder lands:
// a genus-1 control mesh (the paper's 50-vertex torus) through Draco into a
// .dbss with three levels of zero displacements (plain butterfly surface),
// written atomically, read back through the push reader and every level
// decoded by the progressive decoder.
//
// usage: dbss-container-example OUT.dbss
#include <cmath>
#include <cstdio>
#include <numbers>

#include "dbss/decoder/control_mesh.h"
#include "dbss/decoder/progressive.h"
#include "dbss/encoder/control_mesh_codec.h"
#include "dbss/format/reader.h"
#include "dbss/format/writer.h"
#include "dbss/io/file.h"

namespace {

// A torus of `rings` x `sides` quads, two triangles each.
dbss::TriangleMesh torus(uint32_t rings, uint32_t sides, float major, float minor) {
  dbss::TriangleMesh m;
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

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.dbss\n", argv[0]);
    return 1;
  }
  const char* out = argv[1];
  const dbss::TriangleMesh mesh = torus(10, 5, 1.0f, 0.4f);
  auto draco_bytes = dbss::encode_control_mesh(mesh, {});
  if (!draco_bytes.ok()) {
    std::fprintf(stderr, "%s\n", draco_bytes.status().to_string().c_str());
    return 2;
  }

  dbss::format::FileContents c;
  c.header.level_count = 3;
  c.header.control_position_bits = 16;
  c.header.control_vertex_count = 50;
  c.header.control_edge_count = 150;
  c.header.control_triangle_count = 100;
  c.header.bbox_min = {-1.4f, -1.4f, -0.4f};
  c.header.bbox_max = {1.4f, 1.4f, 0.4f};
  c.control_mesh = std::move(draco_bytes).value();
  const dbss::format::MeshCounts control{50, 150, 100};
  for (uint8_t l = 1; l <= 3; ++l) {
    dbss::format::Level level;
    level.index = l;
    level.step = 1e-4f;
    level.q.assign(*dbss::format::odd_vertex_count(control, l), 0);
    c.levels.push_back(std::move(level));
  }
  c.metadata = {{"encoder", "dbss-container-example"}, {"source", "procedural torus 10x5"}};
  auto bytes = dbss::format::serialize(c);
  if (!bytes.ok()) {
    std::fprintf(stderr, "%s\n", bytes.status().to_string().c_str());
    return 2;
  }
  if (auto s = dbss::io::write_file_atomic(out, bytes.value()); !s.ok()) {
    std::fprintf(stderr, "%s\n", s.to_string().c_str());
    return 1;
  }

  // Read back through the file system, one byte range per chunk as a
  // streaming client would see them.
  auto file = dbss::io::read_file(out);
  if (!file.ok()) {
    std::fprintf(stderr, "%s\n", file.status().to_string().c_str());
    return 1;
  }
  const auto r = dbss::format::read_all(file.value());
  if (!r.complete()) {
    std::fprintf(stderr, "%s: %s\n", out, r.status().to_string().c_str());
    return 2;
  }
  std::printf("wrote %s: %zu bytes (control mesh %zu bytes of Draco)\n", out, file.value().size(),
              r.control_payload().size());
  // Decode every level with the progressive decoder, as a viewer would.
  dbss::ProgressiveDecoder decoder;
  if (auto s = decoder.feed(file.value()); !s.ok()) {
    std::fprintf(stderr, "%s: %s\n", out, s.to_string().c_str());
    return 2;
  }
  for (uint32_t l = 0; static_cast<int>(l) <= decoder.ready_level(); ++l) {
    auto mesh = decoder.decode(l);
    if (!mesh.ok()) {
      std::fprintf(stderr, "%s: level %u: %s\n", out, l, mesh.status().to_string().c_str());
      return 2;
    }
    std::printf("level %u: %zu vertices (%zu odd), %zu triangles\n", l, mesh.value().vertex_count(),
                l == 0 ? size_t{0} : r.level(l).q.size(), mesh.value().triangle_count());
  }
  return 0;
}
