// Where a mesh input's level error sits (issue 18): per level, the
// area-weighted distance of the level's triangles (centroids) to the input,
// split by how far the triangle is from the input's boundary curve, and
// the worst triangles.
//   cast_probe [--levels L] [--error E] [--faces F] MESH   (DUMP=PREFIX writes each level as PREFIX<l>.off)
// Found issue 18's elephant floor: level-4 triangles an input edge
// length off the input, their closest input point on a hole's rim.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "dbss/encoder/encode_mesh.h"
#include "dbss/encoder/mesh_input.h"
#include "dbss/encoder/triangle_tree.h"
#include "dbss/io/geometry_files.h"

using namespace dbss;

int main(int argc, char** argv) {
  uint32_t levels = 4;
  double error = 2e-4;
  uint32_t faces = 0;
  std::string path;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--levels") levels = std::atoi(argv[++i]);
    else if (a == "--error") error = std::atof(argv[++i]);
    else if (a == "--faces") faces = std::atoi(argv[++i]);
    else path = a;
  }
  auto in = read_mesh(path);
  if (!in.ok()) return 1;
  EncodeOptions o;
  o.levels = levels;
  o.error = error;
  o.threads = 1;
  o.control.control_faces = faces;
  auto e = encode_mesh(in.value(), o, {});
  if (!e.ok()) { std::fprintf(stderr, "%s\n", e.status().to_string().c_str()); return 1; }
  const Encoding& en = e.value().encoding;
  const TriangleMesh& input = e.value().input;
  const double diag = en.diagonal;
  TriangleTree tree(input);
  MeshSurface surface(input);
  std::printf("bytes %zu diag %g control tris %zu\n", en.bytes.size(), diag, en.levels.triangles[0].size() / 3);
  for (uint32_t l = 0; l <= en.level_count; ++l) {
    if (std::getenv("DUMP")) (void)write_mesh(std::string(std::getenv("DUMP")) + std::to_string(l) + ".off", TriangleMesh{en.levels.positions[l], en.levels.triangles[l]});
    const auto& P = en.levels.positions[l];
    const auto& T = en.levels.triangles[l];
    const size_t nt = T.size() / 3;
    // rim distance bands, in diag units
    const double bands[] = {0.002, 0.005, 0.01, 0.02, 1e9};
    double area_b[5] = {}, err_b[5] = {};
    double atot = 0, etot = 0;
    struct W { double e, a, rim; double c[3]; };
    std::vector<W> worst;
    for (size_t f = 0; f < nt; ++f) {
      const float* a = &P[3 * size_t{T[3 * f]}];
      const float* b = &P[3 * size_t{T[3 * f + 1]}];
      const float* c = &P[3 * size_t{T[3 * f + 2]}];
      double u[3], v[3], ctr[3];
      for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = c[k] - a[k], ctr[k] = (double(a[k]) + b[k] + c[k]) / 3;
      const double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
      const double area = 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
      const double d = tree.distance(ctr) / diag;
      double q[3];
      const double rim = surface.has_boundary() ? surface.closest_boundary_point(ctr, q) / diag : 1e9;
      int k = 0;
      while (rim > bands[k]) ++k;
      area_b[k] += area, err_b[k] += area * d;
      atot += area, etot += area * d;
      worst.push_back({d, area, rim, {ctr[0], ctr[1], ctr[2]}});
    }
    std::printf("level %u: centroid l2t %.3e |", l, etot / atot);
    for (int k = 0; k < 5; ++k)
      std::printf(" rim<%g: area %.1f%% err %.2e share %.0f%% |", bands[k], 100 * area_b[k] / atot,
                  area_b[k] ? err_b[k] / area_b[k] : 0.0, 100 * err_b[k] / etot);
    std::printf("\n");
    {
      // per vertex: distance to the input; is the closest point on the rim
      std::vector<uint8_t> bv(P.size() / 3, 0);
      {
        auto bl = boundary_edges(static_cast<uint32_t>(P.size() / 3), T);
        std::vector<uint64_t> keys;
        for (size_t h = 0; h < T.size(); ++h) { uint32_t a = T[h], b = T[h % 3 == 2 ? h - 2 : h + 1]; keys.push_back(uint64_t{std::min(a,b)} << 32 | std::max(a,b)); }
        std::vector<uint64_t> s2 = keys; std::sort(s2.begin(), s2.end());
        for (size_t h = 0; h < T.size(); ++h) if (std::upper_bound(s2.begin(), s2.end(), keys[h]) - std::lower_bound(s2.begin(), s2.end(), keys[h]) == 1) bv[T[h]] = 1, bv[T[h % 3 == 2 ? h - 2 : h + 1]] = 1;
      }
      size_t n[2] = {}, far[2] = {}, farrim[2] = {};
      double sum[2] = {};
      for (size_t v = 0; v < P.size() / 3; ++v) {
        const double p[3] = {P[3 * v], P[3 * v + 1], P[3 * v + 2]};
        double q[3], r[3];
        const double d = tree.closest_point(p, q) / diag;
        const double dr = surface.has_boundary() ? surface.closest_boundary_point(p, r) / diag : 1e9;
        const int k = bv[v];
        ++n[k]; sum[k] += d;
        if (d > 2e-3) { ++far[k]; farrim[k] += dr < d * 1.01; }
      }
      std::printf("  vertices: interior %zu mean %.2e far(>2e-3) %zu (closest on rim %zu); boundary %zu mean %.2e far %zu (rim %zu)\n",
                  n[0], sum[0] / std::max<size_t>(1, n[0]), far[0], farrim[0], n[1], sum[1] / std::max<size_t>(1, n[1]), far[1], farrim[1]);
    }
    if (l == en.level_count) {
      std::sort(worst.begin(), worst.end(), [](const W& x, const W& y) { return x.e * x.a > y.e * y.a; });
      double cum = 0;
      for (size_t i = 0; i < 30 && i < worst.size(); ++i) {
        cum += worst[i].e * worst[i].a;
        std::printf("  worst %zu: err %.2e area %.2e rim %.2e at %.4f %.4f %.4f cum %.1f%%\n", i, worst[i].e, worst[i].a,
                    worst[i].rim, worst[i].c[0], worst[i].c[1], worst[i].c[2], 100 * cum / etot);
      }
      // error distribution: share of error from triangles with e > x
      for (double x : {1e-4, 3e-4, 1e-3, 3e-3, 1e-2}) {
        double s = 0, ar = 0;
        for (auto& w : worst) if (w.e > x) s += w.e * w.a, ar += w.a;
        std::printf("  err > %g: area %.2f%% share %.1f%%\n", x, 100 * ar / atot, 100 * s / etot);
      }
    }
  }
  return 0;
}
