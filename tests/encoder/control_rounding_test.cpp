// round_along_surface (control_rounding.h): the control vertices on Draco's
// grid, nearer their surface than plain rounding leaves them, and kept
// exactly by Draco.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "../shapes.h"
#include "dbss/decoder/control_mesh.h"
#include "dbss/encoder/control_mesh_codec.h"
#include "dbss/encoder/control_rounding.h"

using namespace dbss;

namespace {

std::vector<std::array<float, 3>> sorted_positions(const TriangleMesh& m) {
  std::vector<std::array<float, 3>> out(m.vertex_count());
  for (size_t v = 0; v < out.size(); ++v) out[v] = {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]};
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("control vertices rounded along their surface: nearer it than plain rounding, within the slide, kept by Draco") {
  // A torus turned off the axes (a surface whose normals are not along the
  // grid's axes, like a scan's) and jittered.
  TriangleMesh torus = test::jitter(test::torus(32, 16), 0.01f, 3);
  for (size_t v = 0; v < torus.vertex_count(); ++v) {
    float* p = &torus.positions[3 * v];
    const double c = std::cos(0.5), s = std::sin(0.5);
    const float x = static_cast<float>(c * p[0] - s * p[2]), z = static_cast<float>(s * p[0] + c * p[2]);
    p[0] = x, p[2] = z;
  }
  for (int bits : {8, 10, 12}) {
    INFO(bits << " bits");
    TriangleMesh placed = torus;
    const ControlRounding r = round_along_surface(placed, bits);
    CHECK(r.vertices == torus.vertex_count());
    REQUIRE(r.grid > 0);
    // Plain rounding leaves about a quarter of a spacing along the normal
    // (a uniform offset per axis); the chosen points a fraction of that.
    INFO("mean offset along the normal: plain " << r.nearest_normal / r.grid << ", chosen " << r.chosen_normal / r.grid << " spacings");
    CHECK(r.nearest_normal > 0.15 * r.grid);
    CHECK(r.chosen_normal < 0.3 * r.nearest_normal);
    // No vertex slides farther than kRoundingSlide spacings along the
    // surface, nor farther off it than plain rounding would leave it (at
    // most half a spacing per axis).
    double worst = 0;
    for (size_t i = 0; i < placed.positions.size(); ++i) worst = std::max(worst, double{std::abs(placed.positions[i] - torus.positions[i])});
    CHECK(worst <= (kRoundingSlide + 0.5) * r.grid * 1.001);
    // Draco keeps them where they were put: its decoded vertices are the
    // placed ones (in its own order), to the bit.
    auto bytes = encode_control_mesh(placed, {bits, 0});
    REQUIRE(bytes.ok());
    auto back = decode_control_mesh(bytes.value(), 1u << 20, 1u << 20);
    REQUIRE(back.ok());
    CHECK(sorted_positions(back.value()) == sorted_positions(placed));
    // Plain rounding is what Draco does without it: the same grid.
    auto plain = encode_control_mesh(torus, {bits, 0});
    REQUIRE(plain.ok());
    auto plain_back = decode_control_mesh(plain.value(), 1u << 20, 1u << 20);
    REQUIRE(plain_back.ok());
    double plain_worst = 0;
    const auto a = sorted_positions(plain_back.value());
    for (const auto& p : a)
      for (int c = 0; c < 3; ++c) {
        const double k = (p[c] - a.front()[c]) / r.grid;  // (only x's minimum is a.front()'s; a check on x alone)
        if (c == 0) plain_worst = std::max(plain_worst, std::abs(k - std::nearbyint(k)));
      }
    CHECK(plain_worst < 1e-2);
  }
}

// `fixed` (a mesh's rim): those vertices take Draco's own rounding, placed
// here so the guard against an edge's two ends on one grid point sees them
// where they end up; the others still slide, and only they are counted.
TEST_CASE("control vertices marked fixed round as Draco does and are not counted as slid") {
  TriangleMesh torus = test::jitter(test::torus(32, 16), 0.01f, 3);
  std::vector<uint8_t> fixed(torus.vertex_count(), 0);
  for (size_t v = 0; v < fixed.size(); v += 2) fixed[v] = 1;
  const int bits = 10;
  TriangleMesh placed = torus;
  const ControlRounding r = round_along_surface(placed, bits, &fixed);
  REQUIRE(r.grid > 0);
  CHECK(r.vertices == torus.vertex_count() - (torus.vertex_count() + 1) / 2);
  // Draco's decode of the plain mesh: each fixed vertex is at its plainly
  // rounded point, which Draco's decode of the placed mesh also holds.
  auto plain = encode_control_mesh(torus, {bits, 0});
  REQUIRE(plain.ok());
  auto plain_back = decode_control_mesh(plain.value(), 1u << 20, 1u << 20);
  REQUIRE(plain_back.ok());
  const auto rounded = sorted_positions(plain_back.value());
  size_t fixed_at_plain = 0, slid = 0;
  for (size_t v = 0; v < fixed.size(); ++v) {
    const std::array<float, 3> p{placed.positions[3 * v], placed.positions[3 * v + 1], placed.positions[3 * v + 2]};
    const bool at_plain = std::binary_search(rounded.begin(), rounded.end(), p);
    if (fixed[v]) fixed_at_plain += at_plain;
    else slid += !at_plain;
  }
  CHECK(fixed_at_plain == (fixed.size() + 1) / 2);
  CHECK(slid > 0);
}
