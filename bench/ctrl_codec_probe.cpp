// What Draco's own options give for a .dbss file's CTRL chunk (issue 18):
// the control mesh a file holds, decoded as the decoder does, encoded again
// at the file's position bits with each connectivity method and position
// prediction scheme Draco offers for a triangle mesh, and each speed 0..10.
// Every variant is decoded back with the decoder's own decode_control_mesh
// and checked to be the same mesh (same vertex positions bit for bit, same
// triangles, up to Draco's renumbering): a row that is not says so.
//
// usage: ctrl_codec_probe FILE.dbss...
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <draco/compression/expert_encode.h>
#include <draco/mesh/mesh.h>

#include "dbss/decoder/control_mesh.h"
#include "dbss/format/reader.h"
#include "dbss/io/file.h"

namespace {

using Tri = std::array<std::array<uint32_t, 3>, 3>;  // three corners' position bits

// The mesh as a sorted list of triangles of positions (bit patterns), each
// rotated to start at its smallest corner (orientation kept).
std::vector<Tri> canonical(const dbss::TriangleMesh& m) {
  std::vector<Tri> out;
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    Tri t;
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) std::memcpy(&t[k][a], &m.positions[3 * size_t{m.triangles[3 * f + k]} + a], 4);
    const int s = static_cast<int>(std::min_element(t.begin(), t.end()) - t.begin());
    std::rotate(t.begin(), t.begin() + s, t.end());
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

struct Variant {
  std::string name;
  int method = -1;      // -1: Draco's choice by speed; 0 sequential; 1 edgebreaker
  int submethod = -1;   // edgebreaker: 0 standard, 2 valence
  int prediction = -2;  // -2: Draco's choice; else a draco::PredictionSchemeMethod
  int speed = 0;
};

std::vector<uint8_t> encode(const dbss::TriangleMesh& in, int bits, const Variant& v, std::string& err) {
  const uint32_t n = static_cast<uint32_t>(in.vertex_count());
  draco::Mesh mesh;
  mesh.set_num_points(n);
  draco::GeometryAttribute ga;
  ga.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
  const int att = mesh.AddAttribute(ga, true, n);
  for (uint32_t i = 0; i < n; ++i)
    mesh.attribute(att)->SetAttributeValue(draco::AttributeValueIndex(i), &in.positions[3 * size_t{i}]);
  for (size_t f = 0; f < in.triangle_count(); ++f) {
    draco::Mesh::Face face;
    for (int k = 0; k < 3; ++k) face[k] = draco::PointIndex(in.triangles[3 * f + k]);
    mesh.AddFace(face);
  }
  draco::ExpertEncoder enc(mesh);
  enc.SetAttributeQuantization(att, bits);
  enc.SetSpeedOptions(v.speed, v.speed);
  if (v.method >= 0) enc.SetEncodingMethod(v.method);
  if (v.submethod >= 0) enc.options().SetGlobalInt("edgebreaker_method", v.submethod);
  if (v.prediction != -2) {
    const draco::Status s = enc.SetAttributePredictionScheme(att, v.prediction);
    if (!s.ok()) {
      err = s.error_msg_string();
      return {};
    }
  }
  draco::EncoderBuffer buf;
  if (const draco::Status s = enc.EncodeToBuffer(&buf); !s.ok()) {
    err = s.error_msg_string();
    return {};
  }
  return std::vector<uint8_t>(buf.data(), buf.data() + buf.size());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: ctrl_codec_probe FILE.dbss...\n");
    return 2;
  }
  std::vector<Variant> variants;
  for (int s = 0; s <= 10; ++s) variants.push_back({"speed " + std::to_string(s), -1, -1, -2, s});
  const char* pred_names[] = {"difference", "parallelogram", "multi-parallelogram", "", "constrained multi-parallelogram"};
  for (int sub : {2, 0})
    for (int p : {0, 1, 4})
      variants.push_back({std::string("edgebreaker ") + (sub == 2 ? "valence" : "standard") + ", " + pred_names[p], 1, sub, p, 0});
  for (int p : {0, 1, 4}) variants.push_back({std::string("sequential, ") + pred_names[p], 0, -1, p, 0});
  for (int s : {2, 5})
    for (int sub : {2, 0})
      variants.push_back({"speed " + std::to_string(s) + ", edgebreaker " + (sub == 2 ? "valence" : "standard") + ", parallelogram", 1, sub, 1, s});

  int bad = 0;
  for (int i = 1; i < argc; ++i) {
    auto bytes = dbss::io::read_file(argv[i]);
    if (!bytes.ok()) {
      std::fprintf(stderr, "%s: %s\n", argv[i], bytes.status().message().c_str());
      return 1;
    }
    const auto reader = dbss::format::read_all(bytes.value());
    if (reader.failed() || !reader.has_control()) {
      std::fprintf(stderr, "%s: not a readable .dbss\n", argv[i]);
      return 1;
    }
    const int bits = reader.header().control_position_bits;
    const auto payload = reader.control_payload();
    const auto mesh = dbss::decode_control_mesh(payload, 1u << 24, 1u << 24);
    if (!mesh.ok()) {
      std::fprintf(stderr, "%s: control mesh: %s\n", argv[i], mesh.status().message().c_str());
      return 1;
    }
    const auto ref = canonical(mesh.value());
    std::printf("%s: %zu control vertices, %zu triangles, %d bits, CTRL payload %zu B (%.1f bits a vertex)\n", argv[i],
                mesh.value().vertex_count(), mesh.value().triangle_count(), bits, payload.size(),
                8.0 * static_cast<double>(payload.size()) / static_cast<double>(mesh.value().vertex_count()));
    for (const Variant& v : variants) {
      std::string err;
      const auto out = encode(mesh.value(), bits, v, err);
      if (out.empty()) {
        std::printf("  %-48s  refused: %s\n", v.name.c_str(), err.c_str());
        continue;
      }
      const auto back = dbss::decode_control_mesh(out, 1u << 24, 1u << 24);
      const bool same = back.ok() && back.value().vertex_count() == mesh.value().vertex_count() && canonical(back.value()) == ref;
      if (!same) ++bad;
      std::printf("  %-48s %6zu B  %+6.1f%%  %5.1f bits/v  %s\n", v.name.c_str(), out.size(),
                  100.0 * (static_cast<double>(out.size()) / static_cast<double>(payload.size()) - 1),
                  8.0 * static_cast<double>(out.size()) / static_cast<double>(mesh.value().vertex_count()),
                  (same ? std::string("same mesh") : back.ok() ? std::string("DIFFERENT MESH") : "decode fails: " + back.status().message()).c_str());
    }
  }
  return bad ? 1 : 0;
}
