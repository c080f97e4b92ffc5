// glTF 2.0 writing: levels of detail as meshes linked by MSFT_lod, through
// tinygltf's serializer.
#include <algorithm>
#include <cstring>
#include <limits>
#include <sstream>

#include "dbss/io/file.h"
#include "dbss/io/gltf.h"
#include "formats.h"
#include "gltf_draco.h"
#include "text.h"
#include "tinygltf_config.h"

namespace dbss {

namespace {

constexpr int kArrayBuffer = 34962;         // bufferView target: vertex attributes
constexpr int kElementArrayBuffer = 34963;  // bufferView target: indices

// Appends `n` bytes to the buffer, then zeros up to a multiple of 4: every
// accessor's offset must be a multiple of its component size.
size_t append_aligned(std::vector<unsigned char>& buffer, const void* data, size_t n) {
  const size_t offset = buffer.size();
  buffer.resize(offset + n);
  if (n != 0) std::memcpy(buffer.data() + offset, data, n);
  buffer.resize((buffer.size() + 3) & ~size_t{3}, 0);
  return offset;
}

int add_view(tinygltf::Model& m, size_t offset, size_t length, int target) {
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = offset;
  v.byteLength = length;
  v.target = target;
  m.bufferViews.push_back(v);
  return static_cast<int>(m.bufferViews.size() - 1);
}

// One level's positions and indices into the buffer, and its mesh; returns
// the mesh index.
int add_level(tinygltf::Model& m, std::vector<unsigned char>& buffer, const GltfLod& lod) {
  const TriangleMesh& mesh = *lod.mesh;
  const size_t nv = mesh.vertex_count();

  tinygltf::Accessor pos;
  pos.bufferView = add_view(m, append_aligned(buffer, mesh.positions.data(), mesh.positions.size() * sizeof(float)),
                            mesh.positions.size() * sizeof(float), kArrayBuffer);
  pos.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  pos.type = TINYGLTF_TYPE_VEC3;
  pos.count = nv;
  // The spec requires POSITION's bounds, and validators compare them with
  // the data exactly: float to double is exact, and the JSON writer prints
  // doubles so they read back to the same value.
  pos.minValues.assign(3, std::numeric_limits<double>::infinity());
  pos.maxValues.assign(3, -std::numeric_limits<double>::infinity());
  for (size_t v = 0; v < nv; ++v)
    for (int a = 0; a < 3; ++a) {
      const double x = mesh.positions[3 * v + a];
      pos.minValues[a] = std::min(pos.minValues[a], x);
      pos.maxValues[a] = std::max(pos.maxValues[a], x);
    }
  m.accessors.push_back(pos);
  const int pos_index = static_cast<int>(m.accessors.size() - 1);

  tinygltf::Accessor idx;
  idx.type = TINYGLTF_TYPE_SCALAR;
  idx.count = mesh.triangles.size();
  // 16-bit indices halve the index bytes; 65535 is reserved for primitive
  // restart, so the largest usable index is 65534.
  if (nv <= 65535) {
    std::vector<uint16_t> small(mesh.triangles.begin(), mesh.triangles.end());
    idx.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    idx.bufferView = add_view(m, append_aligned(buffer, small.data(), small.size() * 2), small.size() * 2, kElementArrayBuffer);
  } else {
    idx.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    idx.bufferView = add_view(m, append_aligned(buffer, mesh.triangles.data(), mesh.triangles.size() * 4),
                              mesh.triangles.size() * 4, kElementArrayBuffer);
  }
  m.accessors.push_back(idx);

  tinygltf::Primitive prim;
  prim.attributes["POSITION"] = pos_index;
  prim.indices = static_cast<int>(m.accessors.size() - 1);
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh gm;
  gm.name = lod.name;
  gm.primitives.push_back(prim);
  m.meshes.push_back(gm);
  return static_cast<int>(m.meshes.size() - 1);
}

// One level as a Draco-compressed primitive: its accessors have no buffer
// view, only the counts and bounds of what Draco decodes to.
Result<int> add_draco_level(tinygltf::Model& m, std::vector<unsigned char>& buffer, const GltfLod& lod, int bits) {
  auto d = io_detail::draco_level(*lod.mesh, bits);
  if (!d.ok()) return d.status();
  const io_detail::DracoLevel& dl = d.value();
  tinygltf::Accessor pos;
  pos.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  pos.type = TINYGLTF_TYPE_VEC3;
  pos.count = dl.points;
  pos.minValues.assign(dl.min, dl.min + 3);
  pos.maxValues.assign(dl.max, dl.max + 3);
  m.accessors.push_back(pos);
  const int pos_index = static_cast<int>(m.accessors.size() - 1);
  tinygltf::Accessor idx;
  idx.type = TINYGLTF_TYPE_SCALAR;
  idx.count = 3 * dl.faces;
  idx.componentType = dl.points <= 65535 ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  m.accessors.push_back(idx);

  // No target: Draco bytes are not GPU data.
  const int view = add_view(m, append_aligned(buffer, dl.bytes.data(), dl.bytes.size()), dl.bytes.size(), 0);
  tinygltf::Value::Object attributes, ext;
  attributes["POSITION"] = tinygltf::Value(dl.position_id);
  ext["bufferView"] = tinygltf::Value(view);
  ext["attributes"] = tinygltf::Value(std::move(attributes));
  tinygltf::Primitive prim;
  prim.attributes["POSITION"] = pos_index;
  prim.indices = static_cast<int>(m.accessors.size() - 1);
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.extensions["KHR_draco_mesh_compression"] = tinygltf::Value(std::move(ext));
  tinygltf::Mesh gm;
  gm.name = lod.name;
  gm.primitives.push_back(prim);
  m.meshes.push_back(gm);
  return static_cast<int>(m.meshes.size() - 1);
}

Status check_lods(std::span<const GltfLod> lods) {
  if (lods.empty()) return Status(ErrorCode::invalid_argument, "glTF: no levels to write");
  for (const GltfLod& l : lods) {
    if (l.mesh == nullptr) return Status(ErrorCode::invalid_argument, "glTF: level '" + l.name + "' has no mesh");
    const TriangleMesh& m = *l.mesh;
    if (m.triangle_count() == 0 || m.triangles.size() % 3 != 0 || m.positions.size() % 3 != 0)
      return Status(ErrorCode::invalid_argument, "glTF: level '" + l.name + "' has no triangles");
    for (uint32_t i : m.triangles)
      if (i >= m.vertex_count())
        return Status(ErrorCode::invalid_argument, "glTF: level '" + l.name + "' has index " + std::to_string(i) +
                                                       " past its " + std::to_string(m.vertex_count()) + " vertices");
  }
  return Status();
}

}  // namespace

std::vector<double> gltf_screen_coverage(std::span<const size_t> triangle_counts) {
  constexpr double kScreenPixels = 1920.0 * 1080.0;
  constexpr double kPixelsPerTriangle = 4.0;
  std::vector<double> out(triangle_counts.size(), 0.0);
  double cap = 1.0;
  for (size_t k = 0; k + 1 < triangle_counts.size(); ++k) {
    // Half the next level's triangles face the viewer.
    const double coarser_fits = kPixelsPerTriangle * 0.5 * static_cast<double>(triangle_counts[k + 1]) / kScreenPixels;
    out[k] = std::min(cap, coarser_fits);
    cap = out[k] / 2;
  }
  return out;
}

Result<std::string> gltf_bytes(std::span<const GltfLod> lods, bool binary, const GltfOptions& options) {
  if (Status s = check_lods(lods); !s.ok()) return s;
  if (options.draco_bits < 0 || options.draco_bits > 30)
    return Status(ErrorCode::invalid_argument, "glTF: Draco position bits must be 0 (none) to 30");
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "dbss " DBSS_IO_VERSION;
  std::vector<unsigned char> buffer;
  std::vector<size_t> triangle_counts;
  bool draco_used = false;
  for (const GltfLod& l : lods) {
    tinygltf::Node n;
    n.name = l.name;
    if (options.draco_bits > 0 && !m.nodes.empty()) {
      auto mesh = add_draco_level(m, buffer, l, options.draco_bits);
      if (!mesh.ok()) return mesh.status();
      n.mesh = mesh.value();
      draco_used = true;
    } else {
      n.mesh = add_level(m, buffer, l);
    }
    m.nodes.push_back(n);
    triangle_counts.push_back(l.mesh->triangle_count());
  }
  if (buffer.size() > (uint64_t{1} << 32) - 1024)
    return Status(ErrorCode::invalid_argument, "glTF: the levels take " + std::to_string(buffer.size()) +
                                                   " bytes, past the 4 GiB a GLB can hold");
  tinygltf::Buffer b;
  b.data = std::move(buffer);
  m.buffers.push_back(std::move(b));

  // The finest level's node is the scene's only node; the coarser ones are
  // reached through its MSFT_lod ids (optional: extensionsUsed, not
  // extensionsRequired, so other viewers just show the finest).
  if (lods.size() > 1) {
    tinygltf::Value::Array ids, coverage;
    for (size_t k = 1; k < lods.size(); ++k) ids.emplace_back(static_cast<int>(k));
    for (double c : gltf_screen_coverage(triangle_counts)) coverage.emplace_back(c);
    tinygltf::Value::Object lod;
    lod["ids"] = tinygltf::Value(std::move(ids));
    m.nodes[0].extensions["MSFT_lod"] = tinygltf::Value(std::move(lod));
    tinygltf::Value::Object extras;
    extras["MSFT_screencoverage"] = tinygltf::Value(std::move(coverage));
    m.nodes[0].extras = tinygltf::Value(std::move(extras));
    m.extensionsUsed.push_back("MSFT_lod");
  }
  if (draco_used) {
    // No uncompressed fallback is stored, so a viewer must decode Draco.
    m.extensionsUsed.push_back("KHR_draco_mesh_compression");
    m.extensionsRequired.push_back("KHR_draco_mesh_compression");
  }
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  m.scenes.push_back(scene);
  m.defaultScene = 0;

  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&m, out, /*prettyPrint=*/!binary, binary))
    return Status(ErrorCode::internal, "glTF: tinygltf could not serialize the model");
  return std::move(out).str();
}

Status write_gltf_lods(const std::string& path, std::span<const GltfLod> lods, const GltfOptions& options) {
  const std::string ext = io_detail::lower_extension(path);
  if (ext != "glb" && ext != "gltf")
    return Status(ErrorCode::invalid_argument, path + ": a glTF file needs the extension .glb or .gltf");
  auto bytes = gltf_bytes(lods, ext == "glb", options);
  if (!bytes.ok()) return Status(bytes.status().code(), path + ": " + bytes.status().message());
  const std::string& b = bytes.value();
  return io::write_file_atomic(path, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(b.data()), b.size()));
}

namespace io_detail {

// The format table's single-mesh writers: one level, no MSFT_lod.
Result<std::string> write_glb(const TriangleMesh& mesh) {
  const GltfLod lod{"mesh", &mesh};
  return gltf_bytes(std::span<const GltfLod>(&lod, 1), true);
}

Result<std::string> write_gltf(const TriangleMesh& mesh) {
  const GltfLod lod{"mesh", &mesh};
  return gltf_bytes(std::span<const GltfLod>(&lod, 1), false);
}

}  // namespace io_detail

}  // namespace dbss
