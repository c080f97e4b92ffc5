// Where dbss's error floor comes from (issue 15): the same control mesh,
// levels encoded by the closed loop (encode_levels) with one ingredient
// changed at a time, each level's reconstruction compared with the true
// mesh.  Points are sampled from the mesh as rd_bench samples them.
//
//   points      what `dbss encode` does (sampling against the local fit,
//               the level's step and dead zone as the encoder picks them)
//   no-dz       the same, plain rounding at every level
//   fine        the same, a step 8 times finer and plain rounding: what
//               quantization costs
//   hit         no-dz with the line's first hit among the points, no fit
//   oracle      displacements cast against the true mesh, the encoder's
//               steps: what sampling from points costs
//   oracle-fine the true mesh and the fine step: the representation's own
//               floor (butterfly + normal displacement on this control mesh)
//
// Per level it prints bytes, the two-sided mean distance over the diagonal,
// and its two halves: truth->level (`t2l`, holes and missed detail) and
// level->truth (`l2t`, bumps and overshoot); and the mean distance of the
// level's vertices to the truth (`vtx`): error at the samples themselves,
// against the surface between them.
//
// --regions: where the finest level's error lies on the truth.  Both
// halves of the two-sided mean are split by the distance (in point
// spacings, sqrt(area / points)) from the true surface's point to the
// nearest edge of the true mesh that bends by more than 2 degrees (a
// faceted truth, such as the eight's 634 triangles, is flat everywhere
// else), and by that edge's bend; each cell gives its share of the area
// and what it adds to each half's mean.  With CGAL (rd_bench's peers) the
// variant `af` is advancing front through the same points, unquantized.
//
// usage: floor_probe [--points N] [--noise F] [--levels L] [--samples S]
//                    [--seed S] [--regions] [--variants a,b,...] [--control-faces F] MESH_FILE...
//   --control-faces: the control mesh's face count (the control choice's
//   quarter candidate, say); default: the encoder's default count
#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "dbss/encoder/encode.h"
#include "dbss/encoder/levels.h"
#include "dbss/encoder/sampling.h"
#include "dbss/encoder/triangle_tree.h"
#include "dbss/io/geometry_files.h"
#include "dbss/measure/mesh_distance.h"
#include "dbss/measure/surface_samples.h"
#ifdef DBSS_HAVE_CGAL
#include "rd_peers.h"
#endif

namespace {

double diagonal(const dbss::TriangleMesh& m) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < m.positions.size(); ++i)
    lo[i % 3] = std::min(lo[i % 3], double{m.positions[i]}), hi[i % 3] = std::max(hi[i % 3], double{m.positions[i]});
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

// The truth's bent edges as points 0.1 spacing apart, each with its bend
// (degrees): the distance to the nearest of them stands for the distance
// to the nearest bent edge, within 0.05 spacing.
struct Kinks {
  dbss::PointCloud pc;
  std::vector<float> bend;
  std::unique_ptr<dbss::PointIndex> index;
};

Kinks bent_edges(const dbss::TriangleMesh& m, double spacing) {
  using V = std::array<double, 3>;
  const auto at = [&](uint32_t v) { return V{m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]}; };
  std::vector<V> normal(m.triangle_count());
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const V a = at(m.triangles[3 * t]), b = at(m.triangles[3 * t + 1]), c = at(m.triangles[3 * t + 2]);
    const V u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    V n{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& x : n) x /= len > 0 ? len : 1;
    normal[t] = n;
  }
  std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> faces;
  for (size_t t = 0; t < m.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[3 * t + k], b = m.triangles[3 * t + (k + 1) % 3];
      faces[{std::min(a, b), std::max(a, b)}].push_back(t);
    }
  Kinks out;
  for (const auto& [edge, f] : faces) {
    if (f.size() != 2) continue;
    const V& n0 = normal[f[0]];
    const V& n1 = normal[f[1]];
    const double bend = std::acos(std::clamp(n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2], -1.0, 1.0)) * 180 / M_PI;
    if (bend < 2) continue;
    const V a = at(edge.first), b = at(edge.second);
    const double len = std::sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
    const int steps = std::max(1, static_cast<int>(std::ceil(len / (0.1 * spacing))));
    for (int i = 0; i <= steps; ++i) {
      const double s = static_cast<double>(i) / steps;
      for (int k = 0; k < 3; ++k) out.pc.xyz.push_back(static_cast<float>(a[k] + s * (b[k] - a[k])));
      out.bend.push_back(static_cast<float>(bend));
    }
  }
  if (out.pc.size() > 0) out.index = std::make_unique<dbss::PointIndex>(out.pc);
  return out;
}

// Rows: distance to the nearest bent edge in spacings; columns: its bend.
constexpr double kNearEdges[] = {0.5, 1, 2, 4, INFINITY};
constexpr double kBends[] = {10, 25, INFINITY};

struct RegionTable {
  double area[5][3] = {}, t2l[5][3] = {}, l2t[5][3] = {};
};

// The cell of a point of the true surface.
std::pair<int, int> region_of(const Kinks& k, const double x[3], double spacing) {
  if (!k.index) return {4, 0};
  const float q[3] = {static_cast<float>(x[0]), static_cast<float>(x[1]), static_cast<float>(x[2])};
  const uint32_t i = k.index->nearest(q);
  double d2 = 0;
  for (int c = 0; c < 3; ++c) d2 += (x[c] - k.pc.xyz[3 * size_t{i} + c]) * (x[c] - k.pc.xyz[3 * size_t{i} + c]);
  const double d = std::sqrt(d2) / spacing;
  int row = 0, col = 0;
  while (d >= kNearEdges[row]) ++row;
  if (row == 4) return {4, 0};
  while (k.bend[i] >= kBends[col]) ++col;
  return {row, col};
}

RegionTable regions(const dbss::TriangleMesh& level, const dbss::TriangleMesh& truth, const dbss::TriangleTree& truth_tree,
                    const Kinks& kinks, double spacing, size_t samples, double diag) {
  RegionTable r;
  const dbss::TriangleTree level_tree(level);
  const std::vector<double> on_truth = dbss::sample_surface(truth, samples / 2, 7);
  const std::vector<double> on_level = dbss::sample_surface(level, samples / 2, 8);
  const double n_truth = static_cast<double>(on_truth.size() / 3), n_level = static_cast<double>(on_level.size() / 3);
  for (size_t i = 0; i < on_truth.size(); i += 3) {
    const auto [row, col] = region_of(kinks, &on_truth[i], spacing);
    r.area[row][col] += 1 / n_truth;
    r.t2l[row][col] += level_tree.distance(&on_truth[i]) / n_truth / diag;
  }
  for (size_t i = 0; i < on_level.size(); i += 3) {
    double foot[3];
    const double d = truth_tree.closest_point(&on_level[i], foot);
    const auto [row, col] = region_of(kinks, foot, spacing);
    r.l2t[row][col] += d / n_level / diag;
  }
  return r;
}

void print_regions(const std::string& name, const RegionTable& r) {
  double t2l = 0, l2t = 0;
  for (int a = 0; a < 5; ++a)
    for (int b = 0; b < 3; ++b) t2l += r.t2l[a][b], l2t += r.l2t[a][b];
  std::printf("  regions of %s: two-sided %.3e = (t2l %.3e + l2t %.3e) / 2; per cell: area share, t2l and l2t added (x1e-6)\n",
              name.c_str(), 0.5 * (t2l + l2t), t2l, l2t);
  static const char* kRow[] = {"< 0.5", "0.5-1", "1-2", "2-4", ">= 4 sp (or no bent edge)"};
  static const char* kCol[] = {"bend < 10", "10-25", ">= 25"};
  for (int a = 0; a < 5; ++a) {
    std::printf("    %-26s", kRow[a]);
    for (int b = 0; b < (a == 4 ? 1 : 3); ++b)
      std::printf(" | %s: %5.1f%% %7.2f %7.2f", a == 4 ? "all" : kCol[b], 100 * r.area[a][b], 1e6 * r.t2l[a][b], 1e6 * r.l2t[a][b]);
    std::printf("\n");
  }
}

}  // namespace

int main(int argc, char** argv) {
  size_t points = 30000, samples = 100000;
  double noise = 0;
  uint32_t levels = 5, seed = 1;
  uint32_t control_faces = 0;  // --control-faces: the control mesh's face count (0: the default)
  bool show_regions = false;
  std::vector<std::string> variants = {"points", "no-dz", "fine", "oracle", "oracle-fine"};
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--points" && i + 1 < argc) points = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--noise" && i + 1 < argc) noise = std::atof(argv[++i]);
    else if (a == "--levels" && i + 1 < argc) levels = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--samples" && i + 1 < argc) samples = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--variants" && i + 1 < argc) variants = split(argv[++i]);
    else if (a == "--seed" && i + 1 < argc) seed = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--regions") show_regions = true;
    else if (a == "--control-faces" && i + 1 < argc) control_faces = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (!a.empty() && a[0] == '-') return std::fprintf(stderr, "floor_probe: unknown option %s\n", a.c_str()), 1;
    else meshes.push_back(a);
  }
  // Like rd_bench's --skip-absent: absent test data skips (exit 77) a
  // developer's run offline, but fails under CI=true.
  const char* ci = std::getenv("CI");
  for (const std::string& path : meshes)
    if (!std::filesystem::exists(path) && !(ci != nullptr && std::string(ci) == "true"))
      return std::fprintf(stderr, "floor_probe: %s absent (scripts/fetch-test-data.sh): skipped\n", path.c_str()), 77;
  for (const std::string& path : meshes) {
    auto mesh = dbss::read_mesh(path);
    if (!mesh.ok()) return std::fprintf(stderr, "floor_probe: %s\n", mesh.status().to_string().c_str()), 1;
    const dbss::TriangleMesh& truth = mesh.value();
    const double diag = diagonal(truth);
    const std::vector<double> p = dbss::sample_surface(truth, points, seed);
    std::mt19937 rng(seed + 1000);
    dbss::PointCloud pc;
    for (double x : p) pc.xyz.push_back(static_cast<float>(noise > 0 ? x + noise * diag * dbss::standard_normal(rng) : x));
    const dbss::PointIndex index(pc);
    dbss::EncodeOptions eo;
    eo.levels = 0;
    eo.control.control_faces = control_faces;
    auto e = dbss::encode_points(index, eo);
    if (!e.ok()) return std::fprintf(stderr, "floor_probe: %s\n", e.status().to_string().c_str()), 1;
    const dbss::Encoding& enc = e.value();
    const dbss::TriangleTree tree(truth);
    const dbss::MeshDistanceOptions probe{samples, 1, 2};
    std::printf("## %s: %zu points, noise %g, step %.3g of the diagonal, control %zu triangles, %zu bytes to level 0\n",
                path.c_str(), pc.size(), noise, enc.step / diag, enc.control.triangle_count(),
                static_cast<size_t>(dbss::prefix_bytes(enc, 0)));
    std::mutex mutex;
    std::vector<double> diffs[6];  // |sample - oracle| over the diagonal by source (and fitted), all levels
    double area = 0;
    for (size_t t = 0; t < truth.triangle_count(); ++t) {
      double c[3][3];
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j) c[k][j] = truth.positions[3 * size_t{truth.triangles[3 * t + k]} + j];
      const double u[3] = {c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2]};
      const double w[3] = {c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2]};
      const double x = u[1] * w[2] - u[2] * w[1], y = u[2] * w[0] - u[0] * w[2], z = u[0] * w[1] - u[1] * w[0];
      area += 0.5 * std::sqrt(x * x + y * y + z * z);
    }
    const double spacing = std::sqrt(area / static_cast<double>(pc.size()));
    const Kinks kinks = show_regions ? bent_edges(truth, spacing) : Kinks{};
    for (const std::string& v : variants) {
      if (v == "af") {
#ifdef DBSS_HAVE_CGAL
        const std::vector<double> xyz(pc.xyz.begin(), pc.xyz.end());
        const dbss::bench::Reconstruction r = dbss::bench::advancing_front(xyz);
        if (!r.failure.empty()) return std::fprintf(stderr, "floor_probe: advancing front: %s\n", r.failure.c_str()), 1;
        const dbss::MeshDistance d = dbss::mesh_distance(r.mesh, truth, probe);
        std::printf("%-12s | %.3e (t2l %.2e l2t %.2e)\n", "af", d.mean() / diag, d.b_to_a_mean / diag, d.a_to_b_mean / diag);
        if (show_regions) print_regions("af", regions(r.mesh, truth, tree, kinks, spacing, samples, diag));
#else
        std::printf("af: built without CGAL\n");
#endif
        continue;
      }
      const bool oracle = v.rfind("oracle", 0) == 0;
      const bool fine = v.find("fine") != std::string::npos;
      dbss::LevelSampler sampler;
      if (oracle) {
        sampler.sample = [&](uint32_t, const double q[3], const double n[3], double half_length) {
          dbss::Sample s;
          double t = 0;
          if (tree.nearest_line_hit(q, n, half_length, t)) s.distance = t;
          else s.clamped = true;
          return s;
        };
      } else {
        // hit: the line's first hit among the points, no surface fit (the
        // paper's sampler).
        const bool fit = v.rfind("hit", 0) != 0;
        const bool widen = dbss::points_are_noisy(index);  // as encode_levels decides
        const bool tight = !widen && dbss::points_are_quiet(index);
        sampler.sample = [&, fit, widen, tight](uint32_t, const double q[3], const double n[3], double half_length) {
          thread_local dbss::SampleScratch scratch;
          const dbss::Sample s = dbss::sample_displacement(index, q, n, half_length, half_length, scratch, fit, nullptr, widen, tight);
          double t = 0;
          if (tree.nearest_line_hit(q, n, half_length, t)) {
            std::lock_guard<std::mutex> lock(mutex);
            const int k = static_cast<int>(s.source) * 2 + (s.fitted ? 1 : 0);
            diffs[k].push_back(std::abs(s.distance - t) / diag);
          }
          return s;
        };
      }
      if (v == "points") sampler.dead_zone = [&](size_t odd, size_t even) { return dbss::dead_zone_steps(odd, pc.size(), even); };
      dbss::LevelEncodeOptions lo;
      lo.levels = levels;
      lo.step = fine ? enc.step / 8 : enc.step;
      lo.threads = 2;
      lo.creases = enc.contents.creases;
      auto out = dbss::encode_levels(enc.control, sampler, lo);
      if (!out.ok()) return std::fprintf(stderr, "floor_probe: %s\n", out.status().to_string().c_str()), 1;
      for (int k = 0; k < 6; ++k) {
        std::vector<double>& d = diffs[k];
        if (d.empty()) continue;
        std::sort(d.begin(), d.end());
        double sum = 0;
        for (double x : d) sum += x;
        static const char* kName[] = {"triangle", "triangle+fit", "plane", "plane+fit", "nearest", "nearest+fit"};
        std::printf("  sample - oracle, %-13s %8zu samples: mean %.2e median %.2e p90 %.2e p99 %.2e\n", kName[k], d.size(),
                    sum / d.size(), d[d.size() / 2], d[d.size() * 9 / 10], d[d.size() * 99 / 100]);
        d.clear();
      }
      std::printf("%-12s", v.c_str());
      size_t bytes = 0;
      for (uint32_t l = 0; l <= levels; ++l) {
        dbss::TriangleMesh m;
        m.positions = out.value().positions[l];
        m.triangles = out.value().triangles[l];
        const dbss::MeshDistance d = dbss::mesh_distance(m, truth, probe);
        double vtx = 0;
        for (size_t i = 0; i < m.vertex_count(); ++i) {
          const double x[3] = {m.positions[3 * i], m.positions[3 * i + 1], m.positions[3 * i + 2]};
          vtx += tree.distance(x);
        }
        vtx /= static_cast<double>(m.vertex_count());
        if (l > 0) bytes += out.value().stats[l - 1].bytes;
        std::printf(" | L%u %6.1fK %.3e (t2l %.2e l2t %.2e vtx %.2e)", l, bytes / 1000.0, d.mean() / diag,
                    d.b_to_a_mean / diag, d.a_to_b_mean / diag, vtx / diag);
      }
      std::printf("\n");
      if (show_regions) {
        dbss::TriangleMesh m;
        m.positions = out.value().positions[levels];
        m.triangles = out.value().triangles[levels];
        print_regions(v + " L" + std::to_string(levels), regions(m, truth, tree, kinks, spacing, samples, diag));
      }
      std::fflush(stdout);
    }
  }
  return 0;
}
