// Creases against no creases: each shape (built-in cube, capped cylinder
// and ridge-roof block, or a mesh file such as the libcgal-demo fandisk) is
// sampled to points (fixed seed, area-uniform, as shape_bench does),
// encoded with --crease-angle off and on, and every level is compared with
// the true mesh.  Prints the feature length found against the true one
// (edges of the true mesh whose dihedral angle is over the threshold), the
// bytes the tags cost, and per level the two-sided mean and the Hausdorff
// distance over the true mesh's diagonal, off and on.
//
// usage: crease_bench [--points N] [--levels L] [--angle DEG] [--samples S] [--skip-absent] [--no-shape] [--split] SHAPE...
//   --split: with crease alignment's edge splits (CreaseOptions::split)
//   --collapse: with the alignment's collapses (CreaseOptions::collapse, off by default)
//   --against-no-collapse: the 'off' columns are creases on without the alignment's collapses
//     (CreaseOptions::collapse), the 'on' columns with them (with --collapse): before/after in one run
//   --against-no-relax: likewise without the flat faces' relaxation (CreaseOptions::relax)
//   --against-relax-beside: 'off' = without the flat vertices beside a line relaxed, 'on' = with them
//     (CreaseOptions::relax_beside_lines)
//   --against-no-valence-flips: likewise without the flips toward valence 6 beside the lines
//     (CreaseOptions::valence_flips), the relaxation after them, untag_flat and relax_beside_lines:
//     the ninth session's before/after (its 'off' columns are main's defaults at 8722690)
//   --against-no-flat-corners: likewise without the corner tags on flat, irregular fans
//     (CreaseOptions::flat_corners): the tenth session's before/after
//   --flat-fan DEG: CreaseOptions::flat_fan_degrees (how flat a fan must be for that tag)
//   CREASE_BENCH_AFTER="vflips=0 beside=1 relax_after=0 untag_flat=1 gap=0 fanfit=0 fancheck=0" (environment):
//     the 'on' run's valence_flips, relax_beside_lines, relax_after_flips, untag_flat, gap_snaps,
//     flat_fan_fit and flat_fan_check set so, for trying combinations
//   --on-only: skip the creases-off encode (its columns print zero): for comparing CREASE_BENCH_AFTER
//     settings run by run at half the cost
//   --against-no-wedge: likewise without the wedge sampling next to creases (CreaseOptions::wedge)
//   --against-no-wedge-gate: likewise with the wedge anywhere, not only near tagged edges (CreaseOptions::wedge_gate)
//   --against-sides-everywhere: likewise with every sample of a tagged file one-sided, with the narrow kernel and no
//     facet hit (CreaseOptions::clean_away off): the fourteenth session's before/after
//   --seed S: the point sampling's seed (default 1): crease figures swing with it (and with
//     QEM's tie order), so judge a change over several
//   --fixed-control: the default face count, not chosen by rate-distortion (EncodeOptions::choose_control)
//   --no-shape: without the control mesh's shaping pass (edge flips, relaxation)
//   CREASE_BENCH_DUMP=DIR (environment): each level written to DIR/SHAPE-{on,off}-L.off and
//   the level-0 tags (edge ends, "c" corners) to DIR/SHAPE-creases.txt, each vertex's offset to the
//   true mesh (x y z per line) to DIR/SHAPE-{on,off}-L.dist, for a closer look
//   CREASE_BENCH_WORST=1 (environment): print each level's farthest sample (where its Hausdorff figure is)
//   --noise F: Gaussian noise of F times the true mesh's diagonal added to the points (seeded by --seed)
//   Tags are also judged against the true mesh's features (edges over the angle): a tagged
//   control edge is true when its midpoint and ends are within 0.5% of the diagonal of one, else
//   false; the true features' length farther than that from every tagged edge is missed.
//   SHAPE: cube, cylinder, roof, sphere, torus (smooth: no crease should be found), or a mesh file (absent with --skip-absent: exit 77 unless CI=true)
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "crease_shapes.h"
#include "shapes.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/mesh_shape.h"
#include "dbss/encoder/open_surface.h"
#include "dbss/encoder/point_input.h"
#include "dbss/io/geometry_files.h"
#include "dbss/encoder/triangle_tree.h"
#include "dbss/measure/mesh_distance.h"
#include "dbss/measure/surface_samples.h"

namespace {

double diagonal(const dbss::TriangleMesh& m) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < m.positions.size(); ++i)
    lo[i % 3] = std::min(lo[i % 3], double{m.positions[i]}), hi[i % 3] = std::max(hi[i % 3], double{m.positions[i]});
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

// Total length of the tagged edges of `m`.
double crease_length(const dbss::TriangleMesh& m, const dbss::format::Creases& c) {
  if (c.empty()) return 0;
  auto t = dbss::build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles).value();
  double sum = 0;
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    if (!c.edge[e]) continue;
    const uint32_t h = t.edge_half[e], u = t.triangles[h], w = t.triangles[dbss::next_half(h)];
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += std::pow(double(m.positions[3 * u + k]) - m.positions[3 * w + k], 2);
    sum += std::sqrt(d2);
  }
  return sum;
}

// The 99th and 99.9th percentiles of both directions' sampled distances
// pooled (same samples and seeds as mesh_distance): the Hausdorff figure is
// one worst sample and swings with the sampling seed; these do not.
// `worst` gets the farthest sample: x y z, 0 when it lies on a (1 on b), its distance.
std::array<double, 2> percentiles(const dbss::TriangleMesh& a, const dbss::TriangleMesh& b, size_t samples, std::array<double, 5>* worst = nullptr) {
  std::vector<double> d;
  double far = -1;
  const auto one_way = [&](const dbss::TriangleMesh& from, const dbss::TriangleMesh& to, uint32_t seed) {
    const std::vector<double> p = dbss::sample_surface(from, samples / 2, seed);
    const dbss::TriangleTree tree(to);
    for (size_t i = 0; i + 2 < p.size(); i += 3) {
      d.push_back(tree.distance(&p[i]));
      if (worst && d.back() > far) far = d.back(), *worst = {p[i], p[i + 1], p[i + 2], seed == 1 ? 0.0 : 1.0, far};
    }
  };
  one_way(a, b, 1);
  one_way(b, a, 2);
  if (d.empty()) return {0, 0};
  std::sort(d.begin(), d.end());
  const auto at = [&](double q) { return d[std::min(d.size() - 1, static_cast<size_t>(q * static_cast<double>(d.size())))]; };
  return {at(0.99), at(0.999)};
}

using Segments = std::vector<std::array<double, 6>>;

Segments tagged_segments(const dbss::TriangleMesh& m, const dbss::format::Creases& c) {
  Segments out;
  if (c.empty()) return out;
  auto t = dbss::build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles).value();
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    if (!c.edge[e]) continue;
    const uint32_t h = t.edge_half[e], u = t.triangles[h], w = t.triangles[dbss::next_half(h)];
    out.push_back({m.positions[3 * u], m.positions[3 * u + 1], m.positions[3 * u + 2], m.positions[3 * w], m.positions[3 * w + 1],
                   m.positions[3 * w + 2]});
  }
  return out;
}

double to_segment(const double p[3], const std::array<double, 6>& s) {
  double d[3], q[3], dd = 0, t = 0;
  for (int k = 0; k < 3; ++k) d[k] = s[3 + k] - s[k], q[k] = p[k] - s[k], dd += d[k] * d[k], t += d[k] * q[k];
  t = dd > 0 ? std::clamp(t / dd, 0.0, 1.0) : 0.0;
  double r = 0;
  for (int k = 0; k < 3; ++k) r += (q[k] - t * d[k]) * (q[k] - t * d[k]);
  return std::sqrt(r);
}

double to_segments(const double p[3], const Segments& s) {
  double best = INFINITY;
  for (const auto& g : s) best = std::min(best, to_segment(p, g));
  return best;
}

// Tagged edges near a true feature (true), not (false), and the true
// features' length not near any tag (missed), within `tol`.
struct TagCheck {
  size_t truly = 0, falsely = 0;
  double missed = 0, total = 0;
};
TagCheck check_tags(const Segments& tags, const Segments& truth, double tol) {
  TagCheck c;
  for (const auto& g : tags) {
    bool near = !truth.empty();
    for (int k = 0; k < 3 && near; ++k) {
      double p[3];
      for (int i = 0; i < 3; ++i) p[i] = g[i] + 0.5 * k * (g[3 + i] - g[i]);
      near = to_segments(p, truth) <= tol;
    }
    near ? ++c.truly : ++c.falsely;
  }
  for (const auto& g : truth) {
    const double len = std::sqrt(std::pow(g[3] - g[0], 2) + std::pow(g[4] - g[1], 2) + std::pow(g[5] - g[2], 2));
    const int n = std::max(1, static_cast<int>(std::ceil(len / (0.5 * tol))));
    for (int j = 0; j < n; ++j) {
      double p[3];
      for (int i = 0; i < 3; ++i) p[i] = g[i] + (j + 0.5) / n * (g[3 + i] - g[i]);
      if (to_segments(p, tags) > tol) c.missed += len / n;
    }
    c.total += len;
  }
  return c;
}


// Where a level's two-sided error sits (CREASE_BENCH_REGIONS=1): each
// sample of either surface is classed by its nearest point on the truth
// (near a true corner, a band from the true feature lines, or a face;
// a face is "curved" when the truth's nearest vertex has a bend under the
// crease angle, as the cylinder's side) and its distance summed per side.
// Prints each class's share of the truth's area and its part of the
// two-sided mean, per side, over the diagonal.
struct RegionTable {
  static constexpr int kClasses = 6;
  static const char* name(int c) {
    static const char* names[kClasses] = {"corner<3%", "line<0.3%", "line<1.5%", "line<5%", "face flat", "face curved"};
    return names[c];
  }
};
void print_regions(const dbss::TriangleMesh& level, const dbss::TriangleMesh& truth, const Segments& features, size_t samples,
                   double diag, double angle, uint32_t l) {
  // True corners: feature-segment ends shared by three or more segments.
  std::vector<std::array<double, 3>> ends;
  for (const auto& g : features) ends.push_back({g[0], g[1], g[2]}), ends.push_back({g[3], g[4], g[5]});
  std::vector<std::array<double, 3>> corners;
  for (const auto& a : ends) {
    int n = 0;
    for (const auto& b : ends) n += a == b;
    if (n >= 3 && std::find(corners.begin(), corners.end(), a) == corners.end()) corners.push_back(a);
  }
  // Curved vertices: two incident triangles bent by 1 degree up to the crease angle.
  const size_t nv = truth.vertex_count();
  std::vector<std::vector<std::array<double, 3>>> normals(nv);
  for (size_t f = 0; f < truth.triangle_count(); ++f) {
    const float* a = &truth.positions[3 * size_t{truth.triangles[3 * f]}];
    const float* b = &truth.positions[3 * size_t{truth.triangles[3 * f + 1]}];
    const float* c = &truth.positions[3 * size_t{truth.triangles[3 * f + 2]}];
    const double e[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
    const double g[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
    std::array<double, 3> n = {e[1] * g[2] - e[2] * g[1], e[2] * g[0] - e[0] * g[2], e[0] * g[1] - e[1] * g[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0)) continue;
    for (double& x : n) x /= len;
    for (int k = 0; k < 3; ++k) normals[truth.triangles[3 * f + k]].push_back(n);
  }
  dbss::PointCloud verts;
  verts.xyz.assign(truth.positions.begin(), truth.positions.end());
  std::vector<uint8_t> curved(nv, 0);
  const double lo = std::cos(angle * 3.14159265358979323846 / 180), hi = std::cos(1.0 * 3.14159265358979323846 / 180);
  for (size_t v = 0; v < nv; ++v)
    for (const auto& a : normals[v])
      for (const auto& b : normals[v]) {
        const double c = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        if (c < hi && c >= lo) curved[v] = 1;
      }
  const dbss::PointIndex vindex(verts);
  const dbss::TriangleTree to_truth(truth), to_level(level);
  const auto classify = [&](const double q[3]) {
    double c[3];
    to_truth.closest_point(q, c);
    for (const auto& k : corners)
      if (std::sqrt(std::pow(c[0] - k[0], 2) + std::pow(c[1] - k[1], 2) + std::pow(c[2] - k[2], 2)) < 0.03 * diag) return 0;
    const double d = to_segments(c, features) / diag;
    if (d < 0.003) return 1;
    if (d < 0.015) return 2;
    if (d < 0.05) return 3;
    const float cf[3] = {float(c[0]), float(c[1]), float(c[2])};
    return curved[vindex.nearest(cf)] ? 5 : 4;
  };
  double sum[2][RegionTable::kClasses] = {}, count[2][RegionTable::kClasses] = {};
  double total[2] = {0, 0};
  for (int side = 0; side < 2; ++side) {
    const dbss::TriangleMesh& from = side == 0 ? level : truth;
    const dbss::TriangleTree& to = side == 0 ? to_truth : to_level;
    const std::vector<double> p = dbss::sample_surface(from, samples / 2, side == 0 ? 1 : 2);
    for (size_t i = 0; i + 2 < p.size(); i += 3) {
      const int k = classify(&p[i]);
      const double d = to.distance(&p[i]);
      sum[side][k] += d, count[side][k] += 1, total[side] += 1;
    }
  }
  std::printf("regions level %u (two-sided mean %.3e of the diagonal): class, share of the truth's area, part of the mean "
              "level->truth + truth->level, mean distance per side\n",
              l, 0.5 * ((sum[0][0] + sum[0][1] + sum[0][2] + sum[0][3] + sum[0][4] + sum[0][5]) / total[0] +
                        (sum[1][0] + sum[1][1] + sum[1][2] + sum[1][3] + sum[1][4] + sum[1][5]) / total[1]) / diag);
  for (int k = 0; k < RegionTable::kClasses; ++k)
    std::printf("  %-12s area %.3f  part %.3e + %.3e  mean %.2e / %.2e\n", RegionTable::name(k), count[1][k] / total[1],
                0.5 * sum[0][k] / total[0] / diag, 0.5 * sum[1][k] / total[1] / diag, count[0][k] > 0 ? sum[0][k] / count[0][k] / diag : 0.0,
                count[1][k] > 0 ? sum[1][k] / count[1][k] / diag : 0.0);
}

struct Run {
  std::vector<size_t> bytes;
  std::vector<double> mean, hausdorff, p99, p999;
  dbss::CreaseStats stats;
  double length = 0;
  size_t tag_bytes = 0;
  std::vector<dbss::LevelStats> levels;
  std::string choice;
  TagCheck tags;
  std::vector<uint8_t> file;  // the .dbss bytes, to say whether creases on wrote the same file as off
  double cpu = 0;             // encode_points' CPU seconds (all threads: std::clock)
  dbss::MeshShape shape;      // the control mesh's shape figures (issue 16 item 0)
};

}  // namespace

int main(int argc, char** argv) {
  size_t points = 40000, samples = 200000;
  uint32_t levels = 4, seed = 1;
  double noise = 0;
  double angle = 30, flat_fan = dbss::CreaseOptions{}.flat_fan_degrees;
  std::vector<std::string> shapes;
  bool skip_absent = false, shaping = true, split = false, against_no_collapse = false, against_no_wedge = false, against_no_relax = false, against_beside = false, against_no_gate = false, against_no_vflips = false, against_no_flat_corners = false, against_sides_everywhere = false, fixed_control = false, collapse = false, on_only = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--points" && i + 1 < argc) points = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--levels" && i + 1 < argc) levels = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--angle" && i + 1 < argc) angle = std::atof(argv[++i]);
    else if (a == "--seed" && i + 1 < argc) seed = static_cast<uint32_t>(std::strtoul(argv[++i], nullptr, 10));
    else if (a == "--samples" && i + 1 < argc) samples = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--skip-absent") skip_absent = true;
    else if (a == "--no-shape") shaping = false;
    else if (a == "--split") split = true;
    else if (a == "--against-no-collapse") against_no_collapse = true;
    else if (a == "--fixed-control") fixed_control = true;
    else if (a == "--against-no-wedge") against_no_wedge = true;
    else if (a == "--against-no-relax") against_no_relax = true;
    else if (a == "--against-relax-beside") against_beside = true;
    else if (a == "--against-no-wedge-gate") against_no_gate = true;
    else if (a == "--against-sides-everywhere") against_sides_everywhere = true;
    else if (a == "--against-no-valence-flips") against_no_vflips = true;
    else if (a == "--against-no-flat-corners") against_no_flat_corners = true;
    else if (a == "--flat-fan" && i + 1 < argc) flat_fan = std::atof(argv[++i]);
    else if (a == "--collapse") collapse = true;
    else if (a == "--on-only") on_only = true;
    else if (a == "--noise" && i + 1 < argc) noise = std::atof(argv[++i]);
    else if (!a.empty() && a[0] == '-') return std::fprintf(stderr, "crease_bench: unknown option %s\n", a.c_str()), 1;
    else shapes.push_back(a);
  }
  if (shapes.empty() || points < 100 || levels > 6 || samples < 2 || !(angle > 0))
    return std::fprintf(stderr, "usage: crease_bench [--points N>=100] [--levels 0..6] [--angle DEG] SHAPE...\n"), 1;
  const char* ci = std::getenv("CI");
  std::printf("%zu points per shape (seed %u), crease angle %g; error: two-sided mean / Hausdorff distance to the true mesh "
              "over its diagonal\n\n",
              points, seed, angle);
  for (const std::string& name : shapes) {
    dbss::TriangleMesh truth;
    if (name == "cube") truth = dbss::test::cube();
    else if (name == "cylinder") truth = dbss::test::capped_cylinder(64, 9);
    else if (name == "roof") truth = dbss::test::roof_block(8);
    else if (name == "sphere") truth = dbss::test::uv_sphere(48, 64);
    else if (name == "torus") truth = dbss::test::torus(96, 48);
    else {
      if (!std::filesystem::exists(name)) {
        if (skip_absent && !(ci != nullptr && std::string(ci) == "true"))
          return std::fprintf(stderr, "crease_bench: %s absent (scripts/fetch-test-data.sh): skipped\n", name.c_str()), 77;
        return std::fprintf(stderr, "crease_bench: %s: no such file\n", name.c_str()), 1;
      }
      auto mesh = dbss::read_mesh(name);
      if (!mesh.ok()) return std::fprintf(stderr, "crease_bench: %s\n", mesh.status().to_string().c_str()), 1;
      truth = std::move(mesh).value();
    }
    const double diag = diagonal(truth);
    const std::string shape = std::filesystem::path(name).stem().string();
    const double true_length = crease_length(truth, dbss::test::creases_from_dihedral(truth, angle));
    std::vector<double> p = dbss::sample_surface(truth, points, seed);
    if (noise > 0) {
      std::mt19937_64 rng(seed * 7919u + 17u);
      std::normal_distribution<double> gauss(0.0, noise * diag);
      for (double& x : p) x += gauss(rng);
    }
    dbss::PointCloud pc;
    pc.xyz.assign(p.begin(), p.end());
    const Segments true_features = tagged_segments(truth, dbss::test::creases_from_dihedral(truth, angle));
    Run runs[2];
    for (int on = on_only ? 1 : 0; on < 2; ++on) {
      dbss::EncodeOptions eo;
      eo.levels = levels;
      const bool against = against_no_collapse || against_no_wedge || against_no_relax || against_beside || against_no_gate || against_no_vflips || against_no_flat_corners || against_sides_everywhere;
      eo.creases.angle_degrees = on || against ? angle : 0;
      // 'on': the defaults (with --collapse, collapses too); 'off' with an
      // --against-no-X: the same less X.
      const dbss::CreaseOptions defaults;
      eo.creases.collapse = (defaults.collapse || collapse) && (on || !against_no_collapse);
      eo.creases.wedge = defaults.wedge && (on || !against_no_wedge);
      eo.creases.relax = defaults.relax && (on || !against_no_relax);
      eo.creases.relax_beside_lines = against_beside ? on != 0 : defaults.relax_beside_lines && (on || !against_no_vflips);
      eo.creases.wedge_gate = defaults.wedge_gate && (on || !against_no_gate);
      eo.creases.clean_away = against_sides_everywhere ? on != 0 : defaults.clean_away;
      eo.creases.valence_flips = defaults.valence_flips && (on || !against_no_vflips);
      eo.creases.untag_flat = defaults.untag_flat && (on || !against_no_vflips);
      eo.creases.flat_corners = defaults.flat_corners && (on || !against_no_flat_corners);
      eo.creases.flat_fan_degrees = flat_fan;
      if (const char* after = std::getenv("CREASE_BENCH_AFTER"); after != nullptr && on) {
        const std::string a = after;
        const auto flag = [&](const char* name, bool& b) {
          const size_t at = a.find(std::string(name) + "=");
          if (at != std::string::npos) b = a[at + std::string(name).size() + 1] == '1';
        };
        flag("vflips", eo.creases.valence_flips), flag("beside", eo.creases.relax_beside_lines);
        flag("relax_after", eo.creases.relax_after_flips), flag("untag_flat", eo.creases.untag_flat);
        flag("slivers", eo.creases.sliver_flips), flag("short", eo.creases.short_collapses);
        flag("gap", eo.creases.gap_snaps), flag("fanfit", eo.creases.flat_fan_fit), flag("fancheck", eo.creases.flat_fan_check);
        flag("shape", eo.creases.shape_after_tags);
      }
      // CREASE_BENCH_SMOOTH=R: CreaseOptions::smooth_ratio (0: without the smooth test, as before it).
      if (const char* r = std::getenv("CREASE_BENCH_SMOOTH")) eo.creases.smooth_ratio = std::atof(r);
      // CREASE_BENCH_RUNS=R: CreaseOptions::chain_run_ratio (0: short chain runs kept untested, as before it).
      if (const char* r = std::getenv("CREASE_BENCH_RUNS")) eo.creases.chain_run_ratio = std::atof(r);
      // CREASE_BENCH_MINSHARE=S: CreaseOptions::min_share (0: any tag kept, as before it).
      if (const char* r = std::getenv("CREASE_BENCH_MINSHARE")) eo.creases.min_share = std::atof(r);
      // CREASE_BENCH_DARTS=R: CreaseOptions::max_dart_share (0: tags in pieces kept, as before it).
      if (const char* r = std::getenv("CREASE_BENCH_DARTS")) eo.creases.max_dart_share = std::atof(r);
      // CREASE_BENCH_BITS=B: the control mesh's Draco bits (EncodeOptions::control_bits; 0: the encoder's rule).
      if (const char* r = std::getenv("CREASE_BENCH_BITS")) eo.control_bits = std::atoi(r);
      // CREASE_BENCH_CLAMP=1: a tagged control mesh clamped onto the points' box faces (CreaseOptions::clamp_to_points).
      if (const char* r = std::getenv("CREASE_BENCH_CLAMP")) eo.creases.clamp_to_points = std::atoi(r) != 0;
      // CREASE_BENCH_SETTLE=1: untagged control vertices off the points settled onto them (CreaseOptions::settle_off_points).
      if (const char* r = std::getenv("CREASE_BENCH_SETTLE")) eo.creases.settle_off_points = std::atoi(r) != 0;
      eo.control.shape.enabled = shaping;
      eo.creases.split = split;
      eo.choose_control = !fixed_control;
      const std::clock_t c0 = std::clock();
      auto e = dbss::encode_points(pc, eo);
      runs[on].cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
      if (!e.ok()) return std::fprintf(stderr, "crease_bench: %s: %s\n", shape.c_str(), e.status().to_string().c_str()), 1;
      const dbss::Encoding& enc = e.value();
      runs[on].stats = enc.creases;
      runs[on].file = enc.bytes;
      runs[on].length = crease_length(enc.control, enc.contents.creases);
      runs[on].tags = check_tags(tagged_segments(enc.control, enc.contents.creases), true_features, 0.005 * diag);
      runs[on].levels = enc.levels.stats;
      runs[on].choice = enc.control_choice;
      if (std::getenv("CREASE_BENCH_REGIONS")) {
        // The scales the error is read against: Draco's control grid, the
        // displacement step and the points' spacing, over the diagonal.
        float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (size_t i = 0; i < enc.control.positions.size(); ++i)
          lo[i % 3] = std::min(lo[i % 3], enc.control.positions[i]), hi[i % 3] = std::max(hi[i % 3], enc.control.positions[i]);
        const double range = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
        const double area = dbss::mesh_area(truth);
        std::printf("scales (of the diagonal): control bits %d, Draco grid %.3e, step %.3e, points' spacing %.3e; %zu control vertices\n",
                    enc.control_bits, range / ((1u << enc.control_bits) - 1) / diag, enc.step / diag,
                    std::sqrt(area / static_cast<double>(points)) / diag, enc.control.vertex_count());
        std::printf("control vertices clamped onto the points' box faces: %zu\n", enc.creases.clamped_to_points);
      }
      runs[on].shape = dbss::mesh_shape(enc.control);
      // CREASE_BENCH_POOR=1: where the control mesh's poor triangles and its
      // highest valence sit against the tags (issue 16 item 0): poor
      // triangles by their count of tagged edges and of vertices on a line
      // or corner.
      if (std::getenv("CREASE_BENCH_POOR") && on) {
        const dbss::TriangleMesh& c = enc.control;
        auto bt = dbss::build_topology(static_cast<uint32_t>(c.vertex_count()), c.triangles);
        if (bt.ok()) {
          const dbss::LevelTopology& t = bt.value();
          const dbss::format::Creases& tg = enc.contents.creases;
          std::vector<uint32_t> lines(t.vertex_count, 0), valence(t.vertex_count, 0);
          std::set<std::pair<uint32_t, uint32_t>> tagged;
          for (uint32_t e = 0; e < t.edge_count(); ++e) {
            const uint32_t u = t.triangles[t.edge_half[e]], w = t.triangles[dbss::next_half(t.edge_half[e])];
            ++valence[u], ++valence[w];
            if (!tg.empty() && tg.edge[e]) ++lines[u], ++lines[w], tagged.insert({std::min(u, w), std::max(u, w)});
          }
          int table[4][4] = {};
          for (size_t f = 0; f < c.triangle_count(); ++f) {
            if (dbss::triangle_quality(c, f) >= dbss::kPoorQuality) continue;
            int te = 0, sv = 0;
            for (int k = 0; k < 3; ++k) {
              const uint32_t a = c.triangles[3 * f + k], b = c.triangles[3 * f + (k + 1) % 3];
              te += tagged.count({std::min(a, b), std::max(a, b)}) ? 1 : 0;
              sv += lines[a] > 0 || (!tg.empty() && tg.corner[a]);
            }
            ++table[te][sv];
          }
          std::printf("poor triangles by tagged edges (rows 0-3) x sharp vertices (columns 0-3):");
          for (int i = 0; i < 4; ++i) std::printf(" [%d %d %d %d]", table[i][0], table[i][1], table[i][2], table[i][3]);
          std::printf("\nvertices over valence 10:");
          for (uint32_t v = 0; v < t.vertex_count; ++v)
            if (valence[v] > 10) std::printf(" %u (%u lines%s)", valence[v], lines[v], !tg.empty() && tg.corner[v] ? ", corner" : "");
          std::printf("\n");
        }
      }
      for (const auto& t : enc.toc)
        if (t.type == dbss::format::kCrea) runs[on].tag_bytes = t.length + 12 + 16;  // data, frame, INDX entry
      // The same file as off: the same levels, so the same figures (and
      // half the measuring on the smooth shapes).
      const bool same_as_off = on == 1 && !on_only && runs[1].file == runs[0].file && std::getenv("CREASE_BENCH_DUMP") == nullptr;
      if (same_as_off) {
        runs[1].bytes = runs[0].bytes, runs[1].mean = runs[0].mean, runs[1].hausdorff = runs[0].hausdorff;
        runs[1].p99 = runs[0].p99, runs[1].p999 = runs[0].p999;
      }
      for (uint32_t l = 0; l <= enc.level_count && !same_as_off; ++l) {
        const dbss::TriangleMesh m{enc.levels.positions[l], enc.levels.triangles[l]};
        if (const char* dump = std::getenv("CREASE_BENCH_DUMP")) {
          const std::string path = std::string(dump) + "/" + shape + (on ? "-on-" : "-off-") + std::to_string(l) + ".off";
          if (FILE* f = std::fopen(path.c_str(), "w")) {
            std::fprintf(f, "OFF\n%zu %zu 0\n", m.vertex_count(), m.triangle_count());
            for (size_t i = 0; i < m.vertex_count(); ++i)
              std::fprintf(f, "%.9g %.9g %.9g\n", m.positions[3 * i], m.positions[3 * i + 1], m.positions[3 * i + 2]);
            for (size_t i = 0; i < m.triangle_count(); ++i)
              std::fprintf(f, "3 %u %u %u\n", m.triangles[3 * i], m.triangles[3 * i + 1], m.triangles[3 * i + 2]);
            std::fclose(f);
          }
          // Each vertex's offset to its nearest point of the true mesh.
          if (FILE* f = std::fopen((path.substr(0, path.size() - 4) + ".dist").c_str(), "w")) {
            const dbss::TriangleTree tree(truth);
            for (size_t i = 0; i < m.vertex_count(); ++i) {
              const double v[3] = {m.positions[3 * i], m.positions[3 * i + 1], m.positions[3 * i + 2]};
              double c[3];
              tree.closest_point(v, c);
              std::fprintf(f, "%.9g %.9g %.9g\n", v[0] - c[0], v[1] - c[1], v[2] - c[2]);
            }
            std::fclose(f);
          }
          if (l == 0 && !enc.contents.creases.empty())
            if (FILE* f = std::fopen((std::string(dump) + "/" + shape + "-creases.txt").c_str(), "w")) {
              auto t = dbss::build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles).value();
              for (uint32_t i = 0; i < t.edge_count(); ++i)
                if (enc.contents.creases.edge[i]) std::fprintf(f, "%u %u\n", t.triangles[t.edge_half[i]], t.triangles[dbss::next_half(t.edge_half[i])]);
              for (uint32_t v = 0; v < t.vertex_count; ++v)
                if (enc.contents.creases.corner[v]) std::fprintf(f, "c %u\n", v);
              std::fclose(f);
            }
        }
        const dbss::MeshDistance d = dbss::mesh_distance(m, truth, {samples, 1, 2});
        runs[on].bytes.push_back(dbss::prefix_bytes(enc, l));
        runs[on].mean.push_back(d.mean() / diag);
        runs[on].hausdorff.push_back(d.max() / diag);
        std::array<double, 5> worst{};
        const std::array<double, 2> pct = percentiles(m, truth, samples, &worst);
        if (std::getenv("CREASE_BENCH_WORST"))
          std::printf("worst %s %s level %u: %.4f%% at %.5f %.5f %.5f (%s)\n", shape.c_str(), on ? "on" : "off", l,
                      100 * worst[4] / diag, worst[0], worst[1], worst[2],
                      worst[3] == 0 ? "on the level" : "on the truth");
        runs[on].p99.push_back(pct[0] / diag), runs[on].p999.push_back(pct[1] / diag);
        if (std::getenv("CREASE_BENCH_REGIONS")) print_regions(m, truth, true_features, samples, diag, angle, l);
      }
    }
    const Run& r = runs[1];
    std::printf("### %s\n", shape.c_str());
    for (int on = against_no_collapse || against_no_wedge || against_no_relax || against_beside || against_no_gate || against_no_vflips || against_no_flat_corners || against_sides_everywhere ? 0 : 1; on < 2; ++on) {
      const dbss::CreaseStats& s = runs[on].stats;
      if (against_no_collapse || against_no_wedge || against_no_relax || against_beside || against_no_gate || against_no_vflips || against_no_flat_corners || against_sides_everywhere) std::printf("%s: ", on ? "after" : "before");
      std::printf("aligned: %zu vertices moved onto feature lines, %zu merged into a neighbour on one, %zu flat-face moves, %zu flat edges flipped toward valence 6, %zu edges flipped and %zu split along "
                  "them, %zu chain edges, %zu slivers flipped, %zu short edges collapsed, %zu flips and %zu moves shaping (%zu rounds undone), %zu vertices off the points settled; creases: %zu edges, %zu corners (%zu on flat fans, %zu dropped by the check), %zu darts, feature length %.3f; tags %zu bytes\n",
                  s.aligned, s.align_collapses, s.align_relaxed, s.align_valence_flips, s.align_flips, s.align_splits, s.chain_edges, s.sliver_flips, s.short_collapses, s.shape_flips, s.shape_moves, s.shape_rounds_undone, s.settled, s.creases, s.corners + s.flat_corners, s.flat_corners, s.flat_corners_dropped, s.darts,
                  runs[on].length / diag, runs[on].tag_bytes);
    }
    std::printf("control mesh: off: %s; on: %s\n", runs[0].choice.c_str(), runs[1].choice.c_str());
    // Issue 16 item 0: the share of control triangles under quality 0.2 and the highest valence.
    std::printf("control shape (on): %.2f%% of triangles under quality %.1f, worst %.3f, max valence %u\n", 100 * r.shape.poor_share,
                dbss::kPoorQuality, r.shape.min_quality, r.shape.max_valence);
    std::printf("creases: %zu edges of %zu tested (%zu gaps closed), %zu corners, %zu darts, %zu vertices snapped (largest move %.2e of the "
                "diagonal); feature length found %.3f, true %.3f (diagonals); tags %zu bytes\n\n",
                r.stats.creases, r.stats.edges_tested, r.stats.gaps_closed, r.stats.corners, r.stats.darts, r.stats.snapped, r.stats.max_snap / diag,
                r.length / diag, true_length / diag, r.tag_bytes);
    std::printf("tags against the true features: %zu true, %zu false edges, missed %.3f of %.3f (diagonals), %zu smooth-rejected, %zu untagged in lone short chain runs, %zu untagged as too few, %zu as in pieces\n\n",
                r.tags.truly, r.tags.falsely, r.tags.missed / diag, r.tags.total / diag, r.stats.smooth_rejected, r.stats.chain_runs_dropped,
                r.stats.too_few_dropped, r.stats.in_pieces_dropped);
    // The file on against off (smooth shapes: a mesh left without tags is
    // given back unaligned, so the same bytes), and what detection costs.
    if (!on_only)
      std::printf("file on %s off (%zu / %zu bytes); encode CPU off %.2f s, on %.2f s (%+.1f%%)\n\n",
                  runs[0].file == runs[1].file ? "identical to" : "differs from", runs[1].file.size(), runs[0].file.size(), runs[0].cpu,
                  runs[1].cpu, 100 * (runs[1].cpu / std::max(1e-9, runs[0].cpu) - 1));
    std::printf("sampler, levels 1..%u (on): clamped", levels);
    for (const auto& ls : r.levels) std::printf(" %zu", ls.clamped);
    std::printf("; nearest-point fallback");
    for (const auto& ls : r.levels) std::printf(" %zu", ls.by_nearest);
    std::printf("; wedge samples (off/on)");
    for (size_t l = 0; l < r.levels.size(); ++l) std::printf(" %zu/%zu", l < runs[0].levels.size() ? runs[0].levels[l].by_wedge : 0, r.levels[l].by_wedge);
    std::printf("; odd vertices");
    for (const auto& ls : r.levels) std::printf(" %zu", ls.odd);
    std::printf("\n\n");
    std::printf("| level | bytes off | bytes on | error off | error on | Hausdorff off | Hausdorff on | p99 off | p99 on | p99.9 off | p99.9 on |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
    if (on_only) runs[0].bytes.assign(runs[1].bytes.size(), 0), runs[0].mean = runs[0].hausdorff = runs[0].p99 = runs[0].p999 = std::vector<double>(runs[1].bytes.size(), 0.0);
    for (size_t l = 0; l < std::min(runs[0].bytes.size(), runs[1].bytes.size()); ++l)
      std::printf("| %zu | %zu | %zu | %.3e | %.3e | %.2f%% | %.2f%% | %.3f%% | %.3f%% | %.3f%% | %.3f%% |\n", l, runs[0].bytes[l], runs[1].bytes[l],
                  runs[0].mean[l], runs[1].mean[l], 100 * runs[0].hausdorff[l], 100 * runs[1].hausdorff[l], 100 * runs[0].p99[l],
                  100 * runs[1].p99[l], 100 * runs[0].p999[l], 100 * runs[1].p999[l]);
    std::printf("\n");
    std::fflush(stdout);
  }
  return 0;
}
