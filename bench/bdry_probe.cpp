// Where a holed mesh's bytes and error go (issue 18): the control mesh's
// Draco bytes (connectivity against positions, and how many control
// vertices sit on the boundary loops), per level the LEVL and BDRY chunks
// (frame included, as the file holds them), and the share of each level's
// error that lies next to the boundary.
//   bdry_probe [--levels L] [--error E] [--cut-holes N] [--hole-radius R] [--bdry-levels MASK] [--bdry-always] MESH
// The error is split both ways.  Level to input: the level's triangles
// (area-weighted distance of a centroid to the input) that touch a
// boundary vertex of the level against the rest.  Input to level: the
// input's triangles within one level edge length (the level's mean
// boundary edge) of the input's boundary curve against the rest.  Each
// is over the diagonal; "rim share" is the part of that direction's mean
// the rim band carries.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "cut_holes.h"
#include "dbss/encoder/control_mesh_codec.h"
#include "dbss/encoder/encode_mesh.h"
#include "dbss/encoder/mesh_input.h"
#include "dbss/encoder/triangle_tree.h"
#include "dbss/io/geometry_files.h"
#include "dbss/measure/mesh_distance.h"

using namespace dbss;

namespace {

struct Split {
  double rim_area = 0, rim_err = 0, area = 0, err = 0;
  double mean() const { return area > 0 ? err / area : 0; }
  double share() const { return err > 0 ? rim_err / err : 0; }
  double rim_area_share() const { return area > 0 ? rim_area / area : 0; }
};

void add_triangle(const float* a, const float* b, const float* c, const TriangleTree& to, bool rim, Split& s) {
  double u[3], v[3], ctr[3];
  for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = c[k] - a[k], ctr[k] = (double(a[k]) + b[k] + c[k]) / 3;
  const double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
  const double area = 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
  const double d = to.distance(ctr);
  s.area += area, s.err += area * d;
  if (rim) s.rim_area += area, s.rim_err += area * d;
}

}  // namespace

int main(int argc, char** argv) {
  uint32_t levels = 4, holes = 0;
  double error = 2e-4, radius = 0.04;
  uint32_t mask = ~0u;
  bool always = false;
  std::string path;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--levels" && i + 1 < argc) levels = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--error" && i + 1 < argc) error = std::atof(argv[++i]);
    else if (a == "--cut-holes" && i + 1 < argc) holes = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--hole-radius" && i + 1 < argc) radius = std::atof(argv[++i]);
    else if (a == "--bdry-always") always = true;
    else if (a == "--bdry-levels" && i + 1 < argc) mask = static_cast<uint32_t>(std::strtoul(argv[++i], nullptr, 0));
    else path = a;
  }
  auto read = read_mesh(path);
  if (!read.ok()) {
    std::fprintf(stderr, "bdry_probe: %s\n", read.status().message().c_str());
    return 1;
  }
  if (holes) read.value() = bench::cut_holes(read.value(), holes, radius);
  EncodeOptions o;
  o.levels = levels;
  o.error = error;
  o.threads = 2;
  MeshEncodeOptions mo;
  mo.boundary_levels = mask;
  mo.boundary_when_pays = !always;
  auto e = encode_mesh(read.value(), o, mo);
  if (!e.ok()) {
    std::fprintf(stderr, "bdry_probe: %s\n", e.status().to_string().c_str());
    return 1;
  }
  const Encoding& en = e.value().encoding;
  const TriangleMesh& input = e.value().input;
  const double diag = en.diagonal;
  const TriangleTree input_tree(input);
  const MeshSurface surface(input);

  // The control mesh: CTRL bytes, and Draco at 1 position bit (positions
  // nearly free: what is left is connectivity and Draco's own header).
  const TriangleMesh& control = en.control;
  const auto cb = boundary_edges(static_cast<uint32_t>(control.vertex_count()), control.triangles);
  std::vector<uint8_t> on_rim(control.vertex_count(), 0);
  {
    // boundary_edges is per edge in the canonical order; mark rim vertices
    // from the half-edges with no twin instead (the same set).
    std::vector<uint64_t> keys;
    for (size_t h = 0; h < control.triangles.size(); ++h) {
      const uint32_t a = control.triangles[h], b = control.triangles[h % 3 == 2 ? h - 2 : h + 1];
      keys.push_back(uint64_t{std::min(a, b)} << 32 | std::max(a, b));
    }
    std::vector<uint64_t> sorted = keys;
    std::sort(sorted.begin(), sorted.end());
    for (size_t h = 0; h < keys.size(); ++h)
      if (std::upper_bound(sorted.begin(), sorted.end(), keys[h]) - std::lower_bound(sorted.begin(), sorted.end(), keys[h]) == 1)
        on_rim[control.triangles[h]] = 1, on_rim[control.triangles[h % 3 == 2 ? h - 2 : h + 1]] = 1;
  }
  size_t rim_vertices = 0;
  for (uint8_t r : on_rim) rim_vertices += r;
  uint64_t ctrl = 0, head = 0;
  std::vector<uint64_t> levl(en.level_count + 1, 0), bdry(en.level_count + 1, 0);
  uint32_t seen = 0;
  for (const format::TocEntry& t : en.toc) {
    if (t.type == format::kCtrl) ctrl = t.length + format::kChunkOverhead, head = t.offset;
    if (t.type == format::kLevl) levl[++seen] = t.length + format::kChunkOverhead;
    if (t.type == format::kBdry) bdry[seen + 1] = t.length + format::kChunkOverhead;
  }
  auto one_bit = encode_control_mesh(control, {1, 0});
  const size_t conn = one_bit.ok() ? one_bit.value().size() : 0;
  std::printf("control: %zu triangles, %zu vertices, %zu on the boundary loops (%.0f%%), %d bits; header+meta %llu B, CTRL %llu B, "
              "of it about %zu B connectivity (Draco at 1 bit) and %llu B positions\n",
              control.triangle_count(), control.vertex_count(), rim_vertices, 100.0 * rim_vertices / control.vertex_count(),
              en.control_bits, static_cast<unsigned long long>(head), static_cast<unsigned long long>(ctrl), conn,
              static_cast<unsigned long long>(ctrl - conn));

  MeshDistanceOptions dopt;
  dopt.samples = 200000;
  dopt.threads = 2;
  std::printf("\n| level | LEVL B | BDRY B | prefix B | boundary odd (moved) | BDRY worth: gain / cost | error | level to input | rim share | input to level | rim share |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (uint32_t l = 0; l <= en.level_count; ++l) {
    const uint64_t prefix = prefix_bytes(en, l);
    const auto& P = en.levels.positions[l];
    const auto& T = en.levels.triangles[l];
    const TriangleMesh m{P, T};
    const MeshDistance d = mesh_distance(m, input, dopt);
    // The level's rim: vertices on a boundary edge, and its mean boundary edge length.
    std::vector<uint8_t> rim(P.size() / 3, 0);
    double rim_len = 0;
    size_t rim_edges = 0;
    {
      std::vector<uint64_t> keys;
      for (size_t h = 0; h < T.size(); ++h) {
        const uint32_t a = T[h], b = T[h % 3 == 2 ? h - 2 : h + 1];
        keys.push_back(uint64_t{std::min(a, b)} << 32 | std::max(a, b));
      }
      std::vector<uint64_t> sorted = keys;
      std::sort(sorted.begin(), sorted.end());
      for (size_t h = 0; h < keys.size(); ++h)
        if (std::upper_bound(sorted.begin(), sorted.end(), keys[h]) - std::lower_bound(sorted.begin(), sorted.end(), keys[h]) == 1) {
          const uint32_t a = T[h], b = T[h % 3 == 2 ? h - 2 : h + 1];
          rim[a] = rim[b] = 1;
          double s = 0;
          for (int k = 0; k < 3; ++k) s += std::pow(double(P[3 * a + k]) - P[3 * b + k], 2.0);
          rim_len += std::sqrt(s), ++rim_edges;
        }
    }
    rim_len = rim_edges ? rim_len / rim_edges : 0;
    Split l2i, i2l;
    for (size_t f = 0; f < T.size() / 3; ++f)
      add_triangle(&P[3 * size_t{T[3 * f]}], &P[3 * size_t{T[3 * f + 1]}], &P[3 * size_t{T[3 * f + 2]}], input_tree,
                   rim[T[3 * f]] || rim[T[3 * f + 1]] || rim[T[3 * f + 2]], l2i);
    const TriangleTree level_tree(m);
    const auto& Q = input.positions;
    const auto& U = input.triangles;
    for (size_t f = 0; f < U.size() / 3; ++f) {
      const float* a = &Q[3 * size_t{U[3 * f]}];
      double c[3] = {}, q[3];
      for (int k = 0; k < 3; ++k) c[k] = (double(a[k]) + Q[3 * size_t{U[3 * f + 1]} + k] + Q[3 * size_t{U[3 * f + 2]} + k]) / 3;
      const bool near = surface.has_boundary() && surface.closest_boundary_point(c, q) < rim_len;
      add_triangle(a, &Q[3 * size_t{U[3 * f + 1]}], &Q[3 * size_t{U[3 * f + 2]}], level_tree, near, i2l);
    }
    const LevelStats* st = l ? &en.levels.stats[l - 1] : nullptr;
    std::printf("| %u | %llu | %llu | %llu | %zu (%zu) | %.3g / %.3g%s | %.2e | %.2e | %.0f%% (area %.1f%%) | %.2e | %.0f%% (area %.1f%%) |\n", l,
                static_cast<unsigned long long>(l ? levl[l] : 0), static_cast<unsigned long long>(bdry[l]),
                static_cast<unsigned long long>(prefix), st ? st->boundary_odd : 0, st ? st->boundary_moved : 0,
                st ? st->boundary_worth.gain : 0.0, st ? st->boundary_worth.cost : 0.0, st && st->boundary_dropped ? " (dropped)" : "",
                d.mean() / diag, l2i.mean() / diag, 100 * l2i.share(), 100 * l2i.rim_area_share(), i2l.mean() / diag,
                100 * i2l.share(), 100 * i2l.rim_area_share());
  }
  return 0;
}
