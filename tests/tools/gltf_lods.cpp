// Prints each level of detail of a glTF file as `dbss export` writes them:
// the scene's node, then the nodes its MSFT_lod extension lists, one line
// each with the node's name, counts, index width and the spec's level hash
// of its positions (spec/decoding.md section 8).  Read with tinygltf
// directly, not through io's reader (which keeps only the scene's finest
// level and merges equal positions), so the CLI test sees what is stored.
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "tinygltf_config.h"

namespace {

const unsigned char* data_of(const tinygltf::Model& m, int accessor, size_t element_size) {
  const tinygltf::Accessor& a = m.accessors.at(static_cast<size_t>(accessor));
  const tinygltf::BufferView& v = m.bufferViews.at(static_cast<size_t>(a.bufferView));
  const std::vector<unsigned char>& b = m.buffers.at(static_cast<size_t>(v.buffer)).data;
  if (v.byteOffset + a.byteOffset + a.count * element_size > b.size()) throw std::runtime_error("accessor past its buffer");
  return b.data() + v.byteOffset + a.byteOffset;
}

void print_node(const tinygltf::Model& m, int node) {
  const tinygltf::Node& n = m.nodes.at(static_cast<size_t>(node));
  const tinygltf::Primitive& p = m.meshes.at(static_cast<size_t>(n.mesh)).primitives.at(0);
  const int pos = p.attributes.at("POSITION");
  const size_t nv = m.accessors.at(static_cast<size_t>(pos)).count;
  const float* xyz = reinterpret_cast<const float*>(data_of(m, pos, 12));
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < 3 * nv; ++i) {
    float f;
    std::memcpy(&f, xyz + i, 4);
    const uint32_t bits = std::bit_cast<uint32_t>(f);
    for (int k = 0; k < 4; ++k) h = (h ^ ((bits >> (8 * k)) & 0xFF)) * 0x100000001b3ull;
  }
  const tinygltf::Accessor& idx = m.accessors.at(static_cast<size_t>(p.indices));
  const int width = idx.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 16 : 32;
  std::printf("%s vertices %zu triangles %zu indices uint%d fnv1a64 %016llx\n", n.name.c_str(), nv, idx.count / 3, width,
              static_cast<unsigned long long>(h));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fputs("usage: gltf_lods FILE.glb\n", stderr);
    return 1;
  }
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  const std::string path = argv[1];
  const bool binary = path.size() > 4 && path.substr(path.size() - 4) == ".glb";
  if (!(binary ? loader.LoadBinaryFromFile(&m, &err, &warn, path) : loader.LoadASCIIFromFile(&m, &err, &warn, path))) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), err.c_str());
    return 1;
  }
  try {
    const int root = m.scenes.at(0).nodes.at(0);
    print_node(m, root);
    const auto lod = m.nodes.at(static_cast<size_t>(root)).extensions.find("MSFT_lod");
    if (lod != m.nodes[static_cast<size_t>(root)].extensions.end()) {
      const tinygltf::Value& ids = lod->second.Get("ids");
      for (size_t k = 0; k < ids.ArrayLen(); ++k) print_node(m, ids.Get(static_cast<int>(k)).GetNumberAsInt());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), e.what());
    return 1;
  }
  return 0;
}
