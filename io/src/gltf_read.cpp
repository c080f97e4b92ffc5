// glTF 2.0 reading (.glb and .gltf): the triangles of the default scene's
// meshes, placed by their nodes' transforms, parsed by tinygltf.  tinygltf
// checks the JSON and the GLB framing; every index into accessors, buffer
// views and buffers, and every byte range, is checked here again before it
// is used, since the input is untrusted.
#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <unordered_map>

#include "formats.h"
#include "text.h"
#include "tinygltf_config.h"

namespace dbss::io_detail {

namespace {

constexpr const char* kNoDraco = "which dbss does not read; decompress it first (e.g. gltf-transform copy)";

using Matrix = std::array<double, 16>;  // column-major, as glTF stores it
constexpr Matrix kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Matrix multiply(const Matrix& a, const Matrix& b) {
  Matrix c{};
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[4 * k + row] * b[4 * col + k];
      c[4 * col + row] = s;
    }
  return c;
}

// A node's local transform: its matrix, or translation * rotation * scale.
Matrix local_transform(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    Matrix m;
    for (int i = 0; i < 16; ++i) m[i] = n.matrix[i];
    return m;
  }
  Matrix t = kIdentity, r = kIdentity, s = kIdentity;
  if (n.translation.size() == 3)
    for (int a = 0; a < 3; ++a) t[12 + a] = n.translation[a];
  if (n.rotation.size() == 4) {
    const double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
    r = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),     0,
         2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),     0,
         2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y), 0,
         0,                       0,                       0,                       1};
  }
  if (n.scale.size() == 3)
    for (int a = 0; a < 3; ++a) s[5 * a] = n.scale[a];
  return multiply(t, multiply(r, s));
}

// An accessor's elements as bytes, its range checked against its buffer view
// and buffer.
struct Elements {
  const unsigned char* data = nullptr;
  size_t stride = 0, count = 0;
  int component_type = 0, components = 0;
  bool normalized = false;
};

class Reader {
 public:
  // `limit`: the most points and triangles the file may expand to (nodes
  // may place one mesh many times; a small file must not ask for
  // gigabytes).
  Reader(const std::string& name, const tinygltf::Model& m, size_t limit) : name_(name), m_(m), limit_(limit) {}

  Status add_scene(GeometryFile& out) {
    const int scene = m_.defaultScene >= 0 ? m_.defaultScene : (m_.scenes.empty() ? -1 : 0);
    if (scene >= static_cast<int>(m_.scenes.size())) return bad(name_, "the default scene " + std::to_string(scene) + " does not exist");
    if (scene < 0) {
      // No scene: nothing would be shown, so take every mesh as it stands.
      for (size_t i = 0; i < m_.meshes.size(); ++i)
        if (Status s = add_mesh(static_cast<int>(i), kIdentity, true, out); !s.ok()) return s;
      return Status();
    }
    // Depth first with an explicit stack (a long chain of nodes must not
    // overflow the call stack), each node visited once: a node reached a
    // second time has two parents or is in a cycle, which glTF forbids, and
    // walking it again could take exponential time.
    struct Visit {
      int node;
      Matrix parent;
      bool parent_identity;
    };
    std::vector<uint8_t> visited(m_.nodes.size(), 0);
    std::vector<Visit> stack;
    const std::vector<int>& roots = m_.scenes[scene].nodes;
    for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.push_back({*r, kIdentity, true});
    while (!stack.empty()) {
      const Visit v = stack.back();
      stack.pop_back();
      if (v.node < 0 || v.node >= static_cast<int>(m_.nodes.size()))
        return bad(name_, "node " + std::to_string(v.node) + " does not exist");
      if (visited[v.node])
        return bad(name_, "node " + std::to_string(v.node) + " is reached twice (two parents, or a cycle in the node hierarchy)");
      visited[v.node] = 1;
      const tinygltf::Node& n = m_.nodes[v.node];
      const bool own_identity = n.matrix.empty() && n.translation.empty() && n.rotation.empty() && n.scale.empty();
      const Matrix world = own_identity ? v.parent : multiply(v.parent, local_transform(n));
      const bool identity = v.parent_identity && own_identity;
      if (n.mesh >= 0)
        if (Status s = add_mesh(n.mesh, world, identity, out); !s.ok()) return s;
      for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) stack.push_back({*c, world, identity});
    }
    return Status();
  }

 private:
  Status add_mesh(int index, const Matrix& world, bool identity, GeometryFile& out) {
    if (index >= static_cast<int>(m_.meshes.size())) return bad(name_, "mesh " + std::to_string(index) + " does not exist");
    const tinygltf::Mesh& mesh = m_.meshes[index];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string where = "mesh " + std::to_string(index) + " primitive " + std::to_string(p);
      if (Status s = add_primitive(mesh.primitives[p], where, world, identity, out); !s.ok()) return s;
    }
    return Status();
  }

  Status add_primitive(const tinygltf::Primitive& prim, const std::string& where, const Matrix& world, bool identity,
                       GeometryFile& out) {
    // A Draco primitive may keep plain accessors as a fallback; without
    // them there is nothing dbss can read.
    const auto position = prim.attributes.find("POSITION");
    if (prim.extensions.count("KHR_draco_mesh_compression") &&
        (position == prim.attributes.end() || position->second < 0 ||
         position->second >= static_cast<int>(m_.accessors.size()) || m_.accessors[position->second].bufferView < 0))
      return bad(name_, where + " is Draco-compressed (KHR_draco_mesh_compression), " + kNoDraco);
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP)
      return bad(name_, where + " draws lines, not a surface or points");
    if (mode != TINYGLTF_MODE_POINTS && mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN)
      return bad(name_, where + " has an unknown mode " + std::to_string(prim.mode));
    const auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) return bad(name_, where + " has no POSITION attribute");
    auto positions = elements(pos->second, where + " POSITION");
    if (!positions.ok()) return positions.status();
    const Elements& p = positions.value();
    if (p.components != 3) return bad(name_, where + " POSITION is not a VEC3 accessor");

    // This primitive's vertices as file vertices: equal positions become
    // one vertex, the first use keeping its place, since glTF splits a
    // vertex wherever its normal or texture coordinate changes and between
    // primitives, which are not holes in the surface.
    if (p.count > limit_ - std::min(limit_, out.points.size()))
      return bad(name_, where + ": the scene places over " + std::to_string(limit_) +
                            " vertices, too many for a file of its size (a mesh instanced that often?)");
    std::vector<uint32_t> vertex(p.count);
    for (size_t v = 0; v < p.count; ++v) {
      double xyz[3];
      for (int a = 0; a < 3; ++a) xyz[a] = component(p, v, a);
      if (!identity) {
        double w[3];
        for (int r = 0; r < 3; ++r) w[r] = world[r] * xyz[0] + world[4 + r] * xyz[1] + world[8 + r] * xyz[2] + world[12 + r];
        std::memcpy(xyz, w, sizeof w);
      }
      if (!push_point(out.points.xyz, xyz))
        return bad(name_, where + " vertex " + std::to_string(v) + ": coordinate is NaN, infinite or over 1e15");
      vertex[v] = merge_last(out.points.xyz);
    }
    if (mode == TINYGLTF_MODE_POINTS) return Status();

    std::vector<uint32_t> corners;
    if (prim.indices >= 0) {
      auto indices = elements(prim.indices, where + " indices");
      if (!indices.ok()) return indices.status();
      const Elements& e = indices.value();
      if (e.components != 1 || e.normalized ||
          (e.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
           e.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
           e.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
        return bad(name_, where + " indices are not unsigned byte, short or int scalars");
      if (e.count / 3 > limit_ - std::min(limit_, out.triangles.size() / 3))
        return bad(name_, where + ": the scene places over " + std::to_string(limit_) +
                              " triangles, too many for a file of its size (a mesh instanced that often?)");
      corners.resize(e.count);
      for (size_t k = 0; k < e.count; ++k) {
        const double i = component(e, k, 0);
        if (i >= static_cast<double>(p.count))
          return bad(name_, where + " index " + std::to_string(k) + " is " + std::to_string(static_cast<uint64_t>(i)) +
                                ", past its " + std::to_string(p.count) + " vertices");
        corners[k] = vertex[static_cast<size_t>(i)];
      }
    } else {
      corners = vertex;
    }
    const size_t first = out.triangles.size();
    if (Status s = add_triangles(corners, mode, where, out.triangles); !s.ok()) return s;
    // A mirroring transform (negative determinant) turns the triangles
    // clockwise, and glTF says to wind them back.
    const double det = world[0] * (world[5] * world[10] - world[9] * world[6]) -
                       world[4] * (world[1] * world[10] - world[9] * world[2]) +
                       world[8] * (world[1] * world[6] - world[5] * world[2]);
    if (!identity && det < 0)
      for (size_t t = first; t < out.triangles.size(); t += 3) std::swap(out.triangles[t + 1], out.triangles[t + 2]);
    return Status();
  }

  Status add_triangles(const std::vector<uint32_t>& c, int mode, const std::string& where, std::vector<uint32_t>& tris) {
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (c.size() % 3 != 0) return bad(name_, where + " has " + std::to_string(c.size()) + " corners, not three per triangle");
      tris.insert(tris.end(), c.begin(), c.end());
      return Status();
    }
    for (size_t k = 2; k < c.size(); ++k) {
      // Strips alternate winding so every triangle faces the same way.
      const bool strip = mode == TINYGLTF_MODE_TRIANGLE_STRIP;
      const uint32_t a = strip ? c[k - 2] : c[0], b = c[k - 1], d = c[k];
      if (strip && k % 2 == 1) {
        tris.insert(tris.end(), {b, a, d});
      } else {
        tris.insert(tris.end(), {a, b, d});
      }
    }
    return Status();
  }

  // Merges the point just appended with an earlier equal one; returns its
  // vertex number.  -0 and +0 are one coordinate.
  uint32_t merge_last(std::vector<float>& xyz) {
    std::array<uint32_t, 3> key;
    for (int a = 0; a < 3; ++a) {
      const float f = xyz[xyz.size() - 3 + a] == 0.0f ? 0.0f : xyz[xyz.size() - 3 + a];
      std::memcpy(&key[a], &f, 4);
    }
    const uint32_t next = static_cast<uint32_t>(xyz.size() / 3 - 1);
    const auto [it, inserted] = seen_.emplace(key, next);
    if (!inserted) xyz.resize(xyz.size() - 3);
    return it->second;
  }

  Result<Elements> elements(int index, const std::string& what) {
    if (index < 0 || index >= static_cast<int>(m_.accessors.size()))
      return bad(name_, what + ": accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& a = m_.accessors[index];
    const std::string acc = what + " (accessor " + std::to_string(index) + ")";
    if (a.sparse.isSparse) return bad(name_, acc + " is sparse, which dbss does not read");
    if (a.bufferView < 0 || a.bufferView >= static_cast<int>(m_.bufferViews.size()))
      return bad(name_, acc + " has no buffer view");
    const tinygltf::BufferView& v = m_.bufferViews[a.bufferView];
    if (v.buffer < 0 || v.buffer >= static_cast<int>(m_.buffers.size()))
      return bad(name_, acc + ": buffer " + std::to_string(v.buffer) + " does not exist");
    const std::vector<unsigned char>& b = m_.buffers[v.buffer].data;
    const int size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
    const int n = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
    if (size <= 0 || n <= 0) return bad(name_, acc + " has an unknown component type or type");
    Elements e;
    e.component_type = a.componentType;
    e.components = n;
    e.normalized = a.normalized;
    e.count = a.count;
    const uint64_t element = uint64_t(size) * uint64_t(n);
    e.stride = v.byteStride != 0 ? v.byteStride : element;
    if (e.stride < element) return bad(name_, acc + ": byte stride " + std::to_string(e.stride) + " is shorter than an element");
    if (v.byteOffset > b.size() || v.byteLength > b.size() - v.byteOffset)
      return bad(name_, acc + ": buffer view " + std::to_string(a.bufferView) + " runs past its buffer's " +
                            std::to_string(b.size()) + " bytes");
    // The last element's end, in 64 bits; counts past the view fail first,
    // so the product cannot overflow.
    if (e.count == 0) return bad(name_, acc + " has no elements");
    if (a.byteOffset > v.byteLength || e.count - 1 > (v.byteLength - a.byteOffset) / e.stride ||
        a.byteOffset + (e.count - 1) * e.stride + element > v.byteLength)
      return bad(name_, acc + ": " + std::to_string(e.count) + " elements run past buffer view " +
                            std::to_string(a.bufferView) + "'s " + std::to_string(v.byteLength) + " bytes");
    e.data = b.data() + v.byteOffset + a.byteOffset;
    return e;
  }

  // Component `c` of element `k` as a number; normalized integers scaled to
  // [0, 1] or [-1, 1] as glTF defines them.
  static double component(const Elements& e, size_t k, int c) {
    const unsigned char* p = e.data + k * e.stride;
    auto get = [&](auto zero) {
      decltype(zero) x;
      std::memcpy(&x, p + c * sizeof x, sizeof x);
      return x;
    };
    switch (e.component_type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: return get(float{});
      case TINYGLTF_COMPONENT_TYPE_DOUBLE: return get(double{});
      case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const double x = get(int8_t{});
        return e.normalized ? std::max(x / 127.0, -1.0) : x;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return e.normalized ? get(uint8_t{}) / 255.0 : get(uint8_t{});
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        const double x = get(int16_t{});
        return e.normalized ? std::max(x / 32767.0, -1.0) : x;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return e.normalized ? get(uint16_t{}) / 65535.0 : get(uint16_t{});
      case TINYGLTF_COMPONENT_TYPE_INT: return get(int32_t{});
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return get(uint32_t{});
      default: return 0;  // unreachable: elements() refused unknown types
    }
  }

  struct KeyHash {
    size_t operator()(const std::array<uint32_t, 3>& k) const noexcept {
      return (size_t{k[0]} * 0x9E3779B97F4A7C15ull) ^ (size_t{k[1]} * 0xC2B2AE3D27D4EB4Full) ^ (size_t{k[2]} + 0x165667B19E3779F9ull);
    }
  };

  const std::string& name_;
  const tinygltf::Model& m_;
  const size_t limit_;
  std::unordered_map<std::array<uint32_t, 3>, uint32_t, KeyHash> seen_;
};

// The file's directory, for a .gltf's external buffers.
std::string directory_of(const std::string& name) {
  const auto slash = name.find_last_of('/');
  return slash == std::string::npos ? "." : slash == 0 ? "/" : name.substr(0, slash);
}

// External buffers ("uri" in a .gltf or a .glb) are read only from the
// glTF's own directory or below it: tinygltf would also try the working
// directory and follow "..", so a hostile file could pull any readable file
// into the geometry.  `user` is the directory's canonical path; paths
// arrive already joined to it and percent-decoded.
bool inside_base(const std::string& path, void* user) {
  namespace fs = std::filesystem;
  const auto& base = *static_cast<const fs::path*>(user);
  if (base.empty()) return false;
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::path(path), ec);
  if (ec) return false;
  const auto [b, q] = std::mismatch(base.begin(), base.end(), p.begin(), p.end());
  return b == base.end() && q != p.end() && fs::is_regular_file(p, ec);
}

bool buffer_file_exists(const std::string& path, void* user) { return inside_base(path, user); }

// No "~" or "$VAR" expansion: the path is what the file says.
std::string keep_path(const std::string& path, void*) { return path; }

bool read_buffer_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!inside_base(path, user) || ec || size > 0xFFFFFFFFull) {
    if (err) *err += "an external buffer is missing, outside the glTF's directory or over 4 GiB; ";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) {
    if (err) *err += "an external buffer could not be read; ";
    return false;
  }
  return true;
}

bool no_write(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

// Images are never decoded: dbss reads geometry only.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

}  // namespace

Result<GeometryFile> parse_gltf(const std::string& name, std::string_view bytes) {
  const bool glb_magic = bytes.size() >= 4 && bytes.substr(0, 4) == "glTF";
  if (lower_extension(name) == "glb" && !glb_magic)
    return bad(name, "not a GLB file (it does not start with the magic 'glTF')");
  if (bytes.size() > 0xFFFFFFFFu) return bad(name, "over 4 GiB, more than a glTF file can hold");
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skip_image, nullptr);
  std::filesystem::path base;
  {
    std::error_code ec;
    base = std::filesystem::canonical(directory_of(name), ec);
    if (ec) base.clear();
  }
  loader.SetFsCallbacks({buffer_file_exists, keep_path, read_buffer_file, no_write, &base});
  std::string err, warn;
  bool loaded = false;
  try {
    if (glb_magic) {
      loaded = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                           static_cast<unsigned int>(bytes.size()), directory_of(name));
    } else {
      loaded = loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()),
                                          directory_of(name));
    }
  } catch (const std::exception& e) {
    // tinygltf reports most faults in `err`, but its JSON library and
    // containers can still throw on malformed input.
    return bad(name, std::string("not a valid glTF file: ") + e.what());
  }
  if (!loaded) {
    // tinygltf refuses Draco primitives' accessors without a buffer view;
    // say why rather than echo that.
    if (bytes.find("\"KHR_draco_mesh_compression\"") != std::string_view::npos)
      return bad(name, std::string("uses Draco-compressed meshes (KHR_draco_mesh_compression), ") + kNoDraco);
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    for (char& c : err)
      if (c == '\n') c = ';';
    return bad(name, "not a valid glTF file: " + (err.empty() ? std::string("tinygltf refused it") : err));
  }
  GeometryFile g;
  Reader reader(name, model, std::max<size_t>(size_t{1} << 20, 64 * bytes.size()));
  if (Status s = reader.add_scene(g); !s.ok()) return s;
  return g;
}

}  // namespace dbss::io_detail
