// Sweeps over a real encoder output: every truncation decodes exactly the
// complete levels (bit for bit as the whole file does), every bit flip is
// refused.
#include <catch2/catch.hpp>

#include <cstring>

#include "dbss/decoder/control_mesh.h"
#include "dbss/decoder/progressive.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/control_mesh.h"
#include "dbss/encoder/control_mesh_codec.h"
#include "dbss/encoder/levels.h"
#include "dbss/format/writer.h"

using namespace dbss;

namespace {
std::vector<uint8_t> encoded_example() {
  auto pc = read_points(std::string(DBSS_SOURCE_DIR) + "/examples/double-torus.xyz");
  REQUIRE(pc.ok());
  auto stages = build_control_mesh(pc.value());
  REQUIRE(stages.ok());
  auto draco = encode_control_mesh(stages.value().control, {});
  auto control = decode_control_mesh(draco.value(), 1 << 20, 1 << 20);
  auto topo = build_topology(static_cast<uint32_t>(control.value().vertex_count()), control.value().triangles);
  const PointIndex index(pc.value());
  LevelEncodeOptions o;
  o.levels = 2;
  auto enc = encode_levels(control.value(), index, 5.0, o);
  REQUIRE(enc.ok());
  format::FileContents c;
  c.header.level_count = 2;
  c.header.control_vertex_count = static_cast<uint32_t>(control.value().vertex_count());
  c.header.control_edge_count = topo.value().edge_count();
  c.header.control_triangle_count = static_cast<uint32_t>(control.value().triangle_count());
  c.header.bbox_min = {-2.1f, -1.3f, -0.3f};
  c.header.bbox_max = {2.1f, 1.3f, 0.3f};
  c.control_mesh = draco.value();
  c.levels = enc.value().levels;
  c.metadata = {{"source", "double-torus.xyz"}};
  return format::serialize(c).value();
}
}  // namespace

TEST_CASE("a real file cut at every offset decodes its complete levels exactly as the whole file") {
  const auto file = encoded_example();
  std::vector<std::vector<float>> whole;
  {
    ProgressiveDecoder d;
    REQUIRE(d.feed(file).ok());
    REQUIRE(d.finish().ok());
    for (uint32_t l = 0; l <= 2; ++l) whole.push_back(d.decode(l).value().copy().positions);
  }
  const format::Reader r = format::read_all(file);
  for (size_t n = 0; n < file.size(); ++n) {
    ProgressiveDecoder d;
    d.feed({file.data(), n});
    REQUIRE(d.finish().code() == ErrorCode::truncated);
    int expect = -1;
    for (const auto& e : r.toc())
      if (e.end() <= n && (e.type == format::kCtrl || e.type == format::kLevl)) ++expect;
    REQUIRE(d.ready_level() == expect);
    if (expect >= 0) {
      auto m = d.decode(static_cast<uint32_t>(expect));
      REQUIRE(m.ok());
      REQUIRE(m.value().positions.size() == whole[expect].size());
      REQUIRE(std::memcmp(m.value().positions.data(), whole[expect].data(), whole[expect].size() * 4) == 0);
    }
  }
}

TEST_CASE("a flipped bit anywhere in a real file is caught") {
  const auto file = encoded_example();
  size_t by_checksum = 0;
  for (size_t i = 0; i < file.size(); ++i) {
    auto bad = file;
    bad[i] ^= static_cast<uint8_t>(1u << (i % 8));
    ProgressiveDecoder d;
    d.feed(bad);
    const Status s = d.finish();
    INFO("byte " << i);
    REQUIRE(!s.ok());
    by_checksum += s.code() == ErrorCode::checksum_mismatch;
  }
  // Everything but the signature and a few length fields is the CRC's.
  CHECK(by_checksum + 64 > file.size());
}
