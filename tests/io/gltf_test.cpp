// glTF through io: levels of detail written by gltf_bytes() hold the decoded
// levels bit for bit (read with tinygltf directly, following MSFT_lod), with
// 16-bit indices exactly when they fit; read_geometry() gets the finest
// level back; node transforms, strips and merged seams are read as glTF
// means them; damaged files are refused with the file named.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "dbss/decoder/progressive.h"
#include "dbss/io/file.h"
#include "dbss/io/geometry_files.h"
#include "dbss/io/gltf.h"
#include "tinygltf_config.h"  // io/src: tinygltf, for an independent look at what was written

#include <draco/compression/decode.h>
#include <nlohmann/json.hpp>

using namespace dbss;
namespace fs = std::filesystem;

namespace {

fs::path scratch() {
  const fs::path d = fs::temp_directory_path() / ("dbss-gltf-test-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// Valid files this test writes stay here for the glTF validator step of
// scripts/test.sh (tests/gltf/validate.mjs); damaged ones go to scratch().
fs::path kept() {
  const fs::path d = DBSS_GLTF_OUT_DIR;
  fs::create_directories(d);
  return d;
}

std::string write_bytes(const fs::path& dir, const std::string& name, std::string_view bytes) {
  const std::string path = (dir / name).string();
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path;
}

// A w x h grid of vertices triangulated into 2(w-1)(h-1) triangles.
TriangleMesh grid(uint32_t w, uint32_t h) {
  TriangleMesh m;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      m.positions.push_back(0.1f * static_cast<float>(x) - 3.3f);
      m.positions.push_back(0.07f * static_cast<float>(y));
      m.positions.push_back(std::sin(0.3f * static_cast<float>(x + y)));
    }
  for (uint32_t y = 0; y + 1 < h; ++y)
    for (uint32_t x = 0; x + 1 < w; ++x) {
      const uint32_t a = y * w + x;
      m.triangles.insert(m.triangles.end(), {a, a + 1, a + w, a + 1, a + w + 1, a + w});
    }
  return m;
}

tinygltf::Model load(const std::string& bytes, bool binary) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                                       static_cast<unsigned>(bytes.size()))
                         : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()), "");
  INFO(err);
  REQUIRE(ok);
  return model;
}

// Level `node`'s mesh as the file stores it, and its index component type.
TriangleMesh node_mesh(const tinygltf::Model& m, int node, int& index_type) {
  const tinygltf::Primitive& p = m.meshes.at(m.nodes.at(node).mesh).primitives.at(0);
  REQUIRE(p.mode == TINYGLTF_MODE_TRIANGLES);
  auto bytes_of = [&](int accessor) {
    const tinygltf::Accessor& a = m.accessors.at(accessor);
    const tinygltf::BufferView& v = m.bufferViews.at(a.bufferView);
    return m.buffers.at(v.buffer).data.data() + v.byteOffset + a.byteOffset;
  };
  const tinygltf::Accessor& pos = m.accessors.at(p.attributes.at("POSITION"));
  REQUIRE(pos.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT);
  TriangleMesh out;
  out.positions.resize(3 * pos.count);
  std::memcpy(out.positions.data(), bytes_of(p.attributes.at("POSITION")), 12 * pos.count);
  const tinygltf::Accessor& idx = m.accessors.at(p.indices);
  index_type = idx.componentType;
  const unsigned char* ib = bytes_of(p.indices);
  for (size_t k = 0; k < idx.count; ++k) {
    if (idx.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
      uint16_t i;
      std::memcpy(&i, ib + 2 * k, 2);
      out.triangles.push_back(i);
    } else {
      REQUIRE(idx.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
      uint32_t i;
      std::memcpy(&i, ib + 4 * k, 4);
      out.triangles.push_back(i);
    }
  }
  return out;
}

std::vector<uint32_t> bits(const std::vector<float>& v) {
  std::vector<uint32_t> b;
  for (float f : v) b.push_back(std::bit_cast<uint32_t>(f));
  return b;
}

}  // namespace

TEST_CASE("glTF export holds every decoded level bit for bit, linked by MSFT_lod, finest in the scene") {
  for (const char* golden : {"torus-4-levels", "bordered-grid-3-levels"}) {
    INFO(golden);
    auto file = io::read_file(std::string(DBSS_SOURCE_DIR) + "/tests/golden/v1/" + golden + ".dbss");
    REQUIRE(file.ok());
    ProgressiveDecoder d;
    REQUIRE(d.feed(file.value()).ok());
    REQUIRE(d.finish().ok());
    std::vector<TriangleMesh> levels;
    for (int l = 0; l <= d.ready_level(); ++l) levels.push_back(d.decode(static_cast<uint32_t>(l)).value().copy());
    REQUIRE(levels.size() >= 4);
    std::vector<GltfLod> lods;
    for (size_t l = levels.size(); l-- > 0;) lods.push_back({"level " + std::to_string(l), &levels[l]});

    for (bool binary : {true, false}) {
      INFO((binary ? "glb" : "gltf"));
      auto bytes = gltf_bytes(lods, binary);
      REQUIRE(bytes.ok());
      write_bytes(kept(), std::string(golden) + (binary ? ".glb" : ".gltf"), bytes.value());
      const tinygltf::Model m = load(bytes.value(), binary);
      REQUIRE(m.scenes.size() == 1);
      REQUIRE(m.scenes[0].nodes == std::vector<int>{0});
      REQUIRE(m.extensionsUsed == std::vector<std::string>{"MSFT_lod"});
      CHECK(m.extensionsRequired.empty());  // optional: other viewers show the finest
      const tinygltf::Value& ids = m.nodes[0].extensions.at("MSFT_lod").Get("ids");
      const tinygltf::Value& coverage = m.nodes[0].extras.Get("MSFT_screencoverage");
      REQUIRE(ids.ArrayLen() == levels.size() - 1);
      REQUIRE(coverage.ArrayLen() == levels.size());
      for (size_t k = 0; k < levels.size(); ++k) {
        const int node = k == 0 ? 0 : ids.Get(static_cast<int>(k - 1)).GetNumberAsInt();
        const size_t level = levels.size() - 1 - k;
        INFO("level " << level);
        CHECK(m.nodes[node].name == "level " + std::to_string(level));
        int index_type = 0;
        const TriangleMesh got = node_mesh(m, node, index_type);
        CHECK(bits(got.positions) == bits(levels[level].positions));
        CHECK(got.triangles == levels[level].triangles);
        CHECK(index_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);  // all under 65,535 vertices
        if (k > 0) CHECK(coverage.Get(static_cast<int>(k)).GetNumberAsDouble() < coverage.Get(static_cast<int>(k - 1)).GetNumberAsDouble());
      }
      CHECK(coverage.Get(static_cast<int>(levels.size() - 1)).GetNumberAsDouble() == 0.0);

      // Through io, only the scene's finest level is read, as it was.
      auto back = parse_geometry(binary ? "lods.glb" : "lods.gltf", bytes.value());
      REQUIRE(back.ok());
      CHECK(bits(back.value().points.xyz) == bits(levels.back().positions));
      CHECK(back.value().triangles == levels.back().triangles);
    }
  }
}

TEST_CASE("glTF export with --draco: coarser levels decode from Draco to the level within the quantization step") {
  auto file = io::read_file(std::string(DBSS_SOURCE_DIR) + "/tests/golden/v1/torus-4-levels.dbss");
  REQUIRE(file.ok());
  ProgressiveDecoder d;
  REQUIRE(d.feed(file.value()).ok());
  REQUIRE(d.finish().ok());
  std::vector<TriangleMesh> levels;
  for (int l = 0; l <= d.ready_level(); ++l) levels.push_back(d.decode(static_cast<uint32_t>(l)).value().copy());
  std::vector<GltfLod> lods;
  for (size_t l = levels.size(); l-- > 0;) lods.push_back({"level " + std::to_string(l), &levels[l]});
  constexpr int kBits = 11;
  GltfOptions options;
  options.draco_bits = kBits;
  auto bytes = gltf_bytes(lods, true, options);
  REQUIRE(bytes.ok());
  const std::string& glb = bytes.value();
  write_bytes(kept(), "torus-draco-11.glb", glb);
  CHECK(glb.size() < gltf_bytes(lods, true).value().size());

  // tinygltf 2.7 cannot load Draco primitives without Draco built in, so
  // the GLB's chunks are read by hand: JSON at byte 20, then BIN.
  uint32_t json_length = 0, bin_length = 0;
  std::memcpy(&json_length, glb.data() + 12, 4);
  std::memcpy(&bin_length, glb.data() + 20 + json_length, 4);
  const nlohmann::json j = nlohmann::json::parse(glb.substr(20, json_length));
  const std::string bin = glb.substr(28 + json_length, bin_length);
  CHECK(j["extensionsRequired"] == nlohmann::json::array({"KHR_draco_mesh_compression"}));
  const nlohmann::json& root = j["nodes"][0];
  REQUIRE(root["extensions"]["MSFT_lod"]["ids"].size() == levels.size() - 1);
  for (size_t k = 0; k < levels.size(); ++k) {
    const size_t level = levels.size() - 1 - k;
    INFO("level " << level);
    const int node = k == 0 ? 0 : root["extensions"]["MSFT_lod"]["ids"][k - 1].get<int>();
    const nlohmann::json& prim = j["meshes"][j["nodes"][node]["mesh"].get<int>()]["primitives"][0];
    const nlohmann::json& pos = j["accessors"][prim["attributes"]["POSITION"].get<int>()];
    const TriangleMesh& want = levels[level];
    if (k == 0) {
      // The finest stays plain and exact.
      REQUIRE(!prim.contains("extensions"));
      const nlohmann::json& view = j["bufferViews"][pos["bufferView"].get<int>()];
      std::vector<float> got(want.positions.size());
      std::memcpy(got.data(), bin.data() + view.value("byteOffset", 0), got.size() * 4);
      CHECK(bits(got) == bits(want.positions));
      continue;
    }
    REQUIRE(!pos.contains("bufferView"));
    const nlohmann::json& ext = prim["extensions"]["KHR_draco_mesh_compression"];
    const nlohmann::json& view = j["bufferViews"][ext["bufferView"].get<int>()];
    draco::DecoderBuffer db;
    db.Init(bin.data() + view.value("byteOffset", 0), view["byteLength"].get<size_t>());
    draco::Decoder decoder;
    auto mesh = decoder.DecodeMeshFromBuffer(&db);
    REQUIRE(mesh.ok());
    const draco::Mesh& m = *mesh.value();
    CHECK(m.num_faces() == want.triangle_count());
    CHECK(m.num_points() == pos["count"].get<size_t>());
    CHECK(j["accessors"][prim["indices"].get<int>()]["count"].get<size_t>() == 3 * want.triangle_count());
    const draco::PointAttribute* p = m.GetAttributeByUniqueId(ext["attributes"]["POSITION"].get<uint32_t>());
    REQUIRE(p != nullptr);
    // Every decoded point lies within Draco's quantization of a vertex of
    // the level, and the accessor's bounds are those of the decoded points.
    float lo[3], hi[3];
    for (int a = 0; a < 3; ++a) lo[a] = hi[a] = want.positions[a];
    for (size_t v = 0; v < want.vertex_count(); ++v)
      for (int a = 0; a < 3; ++a)
        lo[a] = std::min(lo[a], want.positions[3 * v + a]), hi[a] = std::max(hi[a], want.positions[3 * v + a]);
    const float step = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}) / float((1 << kBits) - 1);
    float dmin[3] = {1e30f, 1e30f, 1e30f}, dmax[3] = {-1e30f, -1e30f, -1e30f};
    float worst = 0;
    for (draco::PointIndex i(0); i < m.num_points(); ++i) {
      float x[3];
      p->GetMappedValue(i, x);
      float best = 1e30f;
      for (size_t v = 0; v < want.vertex_count(); ++v) {
        float d2 = 0;
        for (int a = 0; a < 3; ++a) d2 += (x[a] - want.positions[3 * v + a]) * (x[a] - want.positions[3 * v + a]);
        best = std::min(best, d2);
      }
      worst = std::max(worst, std::sqrt(best));
      for (int a = 0; a < 3; ++a) dmin[a] = std::min(dmin[a], x[a]), dmax[a] = std::max(dmax[a], x[a]);
    }
    CHECK(worst <= step);  // half a step per axis, sqrt(3)/2 < 1
    for (int a = 0; a < 3; ++a) {
      CHECK(pos["min"][a].get<double>() == double{dmin[a]});
      CHECK(pos["max"][a].get<double>() == double{dmax[a]});
    }
  }
  // io refuses to read it back, saying why.
  auto back = parse_geometry("draco.glb", glb);
  REQUIRE(!back.ok());
  INFO(back.status().message());
  CHECK(back.status().message().find("draco.glb: uses Draco-compressed meshes") == 0);
}

TEST_CASE("glTF indices are 16-bit up to 65,535 vertices and 32-bit past, and read back") {
  // 65,535 vertices: the largest index is 65,534, under the restart value.
  for (auto [w, h, type] : {std::tuple{257u, 255u, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                            std::tuple{256u, 257u, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT}}) {
    const TriangleMesh m = grid(w, h);
    INFO(m.vertex_count() << " vertices");
    const std::string path =
        (kept() / (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? "grid-uint16.glb" : "grid-uint32.glb")).string();
    REQUIRE(write_mesh(path, m).ok());
    auto file = io::read_file(path);
    REQUIRE(file.ok());
    const tinygltf::Model model = load(std::string(file.value().begin(), file.value().end()), true);
    int index_type = 0;
    const TriangleMesh got = node_mesh(model, 0, index_type);
    CHECK(index_type == type);
    CHECK(got.triangles == m.triangles);
    auto back = read_mesh(path);
    REQUIRE(back.ok());
    CHECK(bits(back.value().positions) == bits(m.positions));
    CHECK(back.value().triangles == m.triangles);
  }
}

TEST_CASE("glTF input: node transforms, strips, seams merged, several meshes") {
  // Positions (0,0,0) (1,0,0) (0,1,0) (1,1,0) and the first again (a texture
  // seam's copy) in one base64 buffer.
  std::vector<float> p = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 0};
  std::string raw(reinterpret_cast<const char*>(p.data()), p.size() * 4);
  static const char kB64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string b64;
  for (size_t i = 0; i < raw.size(); i += 3) {
    uint32_t v = uint32_t(uint8_t(raw[i])) << 16;
    if (i + 1 < raw.size()) v |= uint32_t(uint8_t(raw[i + 1])) << 8;
    if (i + 2 < raw.size()) v |= uint32_t(uint8_t(raw[i + 2]));
    b64 += kB64[v >> 18 & 63];
    b64 += kB64[v >> 12 & 63];
    b64 += i + 1 < raw.size() ? kB64[v >> 6 & 63] : '=';
    b64 += i + 2 < raw.size() ? kB64[v & 63] : '=';
  }
  auto replaced = [](std::string s, const std::string& from, const std::string& to) {
    const auto at = s.find(from);
    REQUIRE(at != std::string::npos);
    return s.replace(at, from.size(), to);
  };
  // Mesh 0: a strip over all five positions; mesh 1: the four from byte 12
  // on ((1,0,0) (0,1,0) (1,1,0) (0,0,0)), on a child node that first has no
  // mesh.
  const std::string gltf = R"({"asset":{"version":"2.0"},
    "buffers":[{"byteLength":60,"uri":"data:application/octet-stream;base64,)" + b64 + R"("}],
    "bufferViews":[{"buffer":0,"byteLength":60}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":5,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
                 {"bufferView":0,"byteOffset":12,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":5}]},
              {"primitives":[{"attributes":{"POSITION":1},"mode":4}]}],
    "nodes":[{"mesh":0,"children":[1]},{"translation":[0,0,2],"scale":[2,2,2]}],
    "scenes":[{"nodes":[0]}],"scene":0})";
  auto g = parse_geometry("strip.gltf", gltf);
  REQUIRE(g.ok());
  // The seam's copy of (0,0,0) is vertex 0; every other strip triangle is
  // flipped to keep the first one's winding.
  CHECK(g.value().points.xyz == std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
  CHECK(g.value().triangles == std::vector<uint32_t>{0, 1, 2, 2, 1, 3, 2, 3, 0});

  // Mesh 1 on node 1 as a non-indexed triangle list has 4 corners: refused.
  const std::string two = replaced(gltf, R"({"translation")", R"({"mesh":1,"translation")");
  auto four = parse_geometry("list.gltf", two);
  REQUIRE(!four.ok());
  CHECK(four.status().message().find("list.gltf: mesh 1 primitive 0 has 4 corners, not three per triangle") != std::string::npos);
  // As points, scaled by 2 and moved by (0,0,2).
  auto pts = parse_geometry("points.gltf", replaced(two, R"("mode":4)", R"("mode":0)"));
  REQUIRE(pts.ok());
  CHECK(pts.value().points.xyz ==
        std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 0, 2, 0, 2, 2, 2, 2, 2, 0, 0, 2});
  CHECK(pts.value().triangles == std::vector<uint32_t>{0, 1, 2, 2, 1, 3, 2, 3, 0});

  // The buffer in a file beside the .gltf, found from the .gltf's directory
  // whatever the working directory; a missing one is refused by name.
  write_bytes(scratch(), "strip.bin", raw);
  const std::string beside = replaced(gltf, "data:application/octet-stream;base64," + b64, "strip.bin");
  auto ext = read_geometry(write_bytes(scratch(), "beside.gltf", beside));
  REQUIRE(ext.ok());
  CHECK(ext.value().points.xyz == g.value().points.xyz);
  CHECK(ext.value().triangles == g.value().triangles);
  auto missing = read_geometry(write_bytes(scratch(), "nobin.gltf", replaced(beside, "strip.bin", "gone.bin")));
  REQUIRE(!missing.ok());
  INFO(missing.status().message());
  CHECK(missing.status().message().find("nobin.gltf: not a valid glTF file") != std::string::npos);
  CHECK(missing.status().message().find("gone.bin") != std::string::npos);
  // Buffers come only from the .gltf's directory or below: "../" is
  // refused even where the file exists.
  fs::create_directories(scratch() / "sub");
  auto up = read_geometry(write_bytes(scratch() / "sub", "up.gltf", replaced(beside, "strip.bin", "../strip.bin")));
  REQUIRE(!up.ok());
  CHECK(up.status().message().find("up.gltf: not a valid glTF file") != std::string::npos);

  // A mirroring node (negative determinant) winds its triangles back.
  auto mirrored = parse_geometry("mirror.gltf", replaced(gltf, R"("nodes":[{"mesh":0,)", R"("nodes":[{"mesh":0,"scale":[-1,1,1],)"));
  REQUIRE(mirrored.ok());
  CHECK(mirrored.value().points.xyz == std::vector<float>{0, 0, 0, -1, 0, 0, 0, 1, 0, -1, 1, 0});
  CHECK(mirrored.value().triangles == std::vector<uint32_t>{0, 2, 1, 2, 3, 1, 2, 0, 3});

  // A node reached twice (listed twice, or in a cycle) is refused, not
  // walked again.
  for (const auto& [from, to] : {std::pair<std::string, std::string>{R"("nodes":[0])", R"("nodes":[0,0])"},
                                 {R"("scale":[2,2,2]})", R"("scale":[2,2,2],"children":[0]})"}}) {
    auto twice = parse_geometry("twice.gltf", replaced(gltf, from, to));
    REQUIRE(!twice.ok());
    CHECK(twice.status().message().find("twice.gltf: node 0 is reached twice") != std::string::npos);
  }
}

TEST_CASE("damaged glTF files are refused with the file named") {
  const TriangleMesh m = grid(4, 3);
  const GltfLod lod{"mesh", &m};
  const std::string glb = gltf_bytes(std::span<const GltfLod>(&lod, 1), true).value();
  const std::string text = gltf_bytes(std::span<const GltfLod>(&lod, 1), false).value();

  auto refused = [](const std::string& name, const std::string& bytes, const std::string& why) {
    INFO(name << ": expecting '" << why << "'");
    auto r = read_geometry(write_bytes(scratch(), name, bytes));
    REQUIRE(!r.ok());
    INFO(r.status().message());
    CHECK(r.status().message().find((scratch() / name).string() + ": ") == 0);
    CHECK(r.status().message().find(why) != std::string::npos);
  };
  // Every cut of the GLB fails cleanly (ASan checks the reads).
  for (size_t n = 0; n < glb.size(); n += (n < 64 ? 1 : 7)) {
    auto r = parse_geometry("cut.glb", glb.substr(0, n));
    INFO(n << " bytes");
    REQUIRE(!r.ok());
    CHECK(r.status().message().find("cut.glb: ") == 0);
  }
  refused("magic.glb", "gLTF" + glb.substr(4), "does not start with the magic 'glTF'");
  refused("empty.gltf", "", "not a valid glTF file");
  refused("json.gltf", text.substr(0, text.size() / 2), "not a valid glTF file");

  // An index past the vertices: the last index (uint16) set to 12 of 12.
  std::string bad_index = glb;
  // The binary chunk ends with the 36 uint16 indices (72 bytes, no padding).
  bad_index[bad_index.size() - 2] = 12;
  bad_index[bad_index.size() - 1] = 0;
  refused("index.glb", bad_index, "index 35 is 12, past its 12 vertices");

  std::string missing = text;
  missing.replace(missing.find("\"indices\": 1"), 12, "\"indices\": 7");
  refused("accessor.gltf", missing, "indices accessor out of bounds");  // caught by tinygltf

  std::string long_count = text;
  long_count.replace(long_count.find("\"count\": 12"), 11, "\"count\": 13");
  refused("count.gltf", long_count, "13 elements run past buffer view 0's 144 bytes");
}

TEST_CASE("screen coverage hints fall with each coarser level and end at 0") {
  const std::vector<size_t> counts = {16'000'000, 4'000'000, 1'000'000, 250'000, 62'500, 100};
  const std::vector<double> c = gltf_screen_coverage(counts);
  REQUIRE(c.size() == counts.size());
  CHECK(c[0] == 1.0);  // 4M triangles under 1 pixel each at full screen: capped
  CHECK(c[1] == 0.5);  // capped at half the level before
  for (size_t k = 1; k < c.size(); ++k) CHECK(c[k] <= c[k - 1] / 2);
  CHECK(c.back() == 0.0);
  // Where the next level's visible half of 250,000 triangles averages 4 pixels.
  CHECK(c[2] == Approx(4.0 * 0.5 * 250'000 / (1920.0 * 1080.0)));
}
