// Where level 1's error comes from beside feature lines (issue 16, the L0 ->
// L1 rise).  Each shape is sampled and encoded with creases on as
// crease_bench does; its control mesh and tags are then refined once more
// by the decoder's own step to find every level-1 odd vertex's undisplaced
// (stencil) point and normal, and the encoded level 1 gives the integer the
// encoder chose for it.  Odd vertices are classed by their parent edge:
//
//   crease   a tagged edge (four-point rule along the crease, bisector normal)
//   dart     an untagged edge with an end that is a dart (one crease edge)
//   side     an untagged edge with one sharp end (a chain vertex): the
//            plain edges from a face onto its line
//   bridge   an untagged edge with both ends sharp, not a crease
//   smooth   neither end sharp
//
// Per class: count, share of the summed level-1 vertex distance to the true
// mesh, the mean distance of the stencil points, of the encoded vertices, of
// the vertices had the encoder chosen the true surface's own hit along the
// normal (oracle q), and the best integer for the true distance (best q,
// the lowest distance over the integers near the oracle's).  Then the whole
// levels against the truth with the points' sampler and with the oracle
// sampler (the same control mesh and tags), and with a step 8 times finer.
//
// With --at L (1..levels) the odd vertices of level L instead (the levels
// before it replayed from the file's integers); past level 1, or with
// --bins, classed by the stencil point's distance from the nearest true
// feature line rather than by parent edge.
//
// usage: crease_rise_probe [--points N] [--seed S] [--levels L] [--at L] [--bins] [--samples S] SHAPE...
//   SHAPE: cube, cylinder, roof, or a mesh file
//   PROBE_DUMP=CLASS (environment): each odd vertex of that class (its number in the table, from 0)
//     whose sample is over PROBE_MIN (default 1e-3) of the diagonal from the truth's hit: point,
//     normal, truth, sample; PROBE_ODD=K: the 32 points nearest odd vertex K and their normals
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "crease_shapes.h"
#include "shapes.h"
#include "dbss/decoder/level_refiner.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/crease_align.h"
#include "dbss/encoder/crease_lines.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/sampling.h"
#include "dbss/encoder/levels.h"
#include "dbss/encoder/triangle_tree.h"
#include "dbss/io/geometry_files.h"
#include "dbss/measure/mesh_distance.h"
#include "dbss/measure/surface_samples.h"

namespace {

double diagonal(const dbss::TriangleMesh& m) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < m.positions.size(); ++i)
    lo[i % 3] = std::min(lo[i % 3], double{m.positions[i]}), hi[i % 3] = std::max(hi[i % 3], double{m.positions[i]});
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

enum Class { kCrease, kDart, kSide, kBridge, kSmooth, kClasses };
const char* kClassName[] = {"crease", "dart", "side", "bridge", "smooth"};
// Past level 1 (or with --bins): by the stencil point's distance from the
// nearest true feature line, over the diagonal.
const double kBin[] = {0.001, 0.005, 0.02, INFINITY};
const char* kBinName[] = {"< 0.1% from a line", "0.1-0.5%", "0.5-2%", "> 2%"};

double segment_distance(const double p[3], const float* a, const float* b) {
  double ab[3], ap[3], l2 = 0, t = 0;
  for (int c = 0; c < 3; ++c) ab[c] = double(b[c]) - a[c], ap[c] = p[c] - a[c], l2 += ab[c] * ab[c], t += ab[c] * ap[c];
  t = l2 > 0 ? std::clamp(t / l2, 0.0, 1.0) : 0;
  double d2 = 0;
  for (int c = 0; c < 3; ++c) d2 += std::pow(ap[c] - t * ab[c], 2);
  return std::sqrt(d2);
}

struct Odd {
  double p[3], n[3];
  bool hit = false;
  double t = 0;  // the truth's hit along n
  dbss::Sample s;  // the points' sample, as encode_levels takes it
};

}  // namespace

int main(int argc, char** argv) {
  size_t points = 40000, samples = 200000;
  uint32_t seed = 1, levels = 3, at_level = 1;
  bool bins = false;
  std::vector<std::string> shapes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--points" && i + 1 < argc) points = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--seed" && i + 1 < argc) seed = static_cast<uint32_t>(std::strtoul(argv[++i], nullptr, 10));
    else if (a == "--levels" && i + 1 < argc) levels = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--bins") bins = true;
    else if (a == "--at" && i + 1 < argc) at_level = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--samples" && i + 1 < argc) samples = std::strtoull(argv[++i], nullptr, 10);
    else if (!a.empty() && a[0] == '-') return std::fprintf(stderr, "crease_rise_probe: unknown option %s\n", a.c_str()), 1;
    else shapes.push_back(a);
  }
  if (shapes.empty() || levels < 1 || at_level < 1 || at_level > levels) return std::fprintf(stderr, "usage: crease_rise_probe [--points N] [--seed S] [--levels L>=1] SHAPE...\n"), 1;
  for (const std::string& name : shapes) {
    dbss::TriangleMesh truth;
    if (name == "cube") truth = dbss::test::cube();
    else if (name == "cylinder") truth = dbss::test::capped_cylinder(64, 9);
    else if (name == "roof") truth = dbss::test::roof_block(8);
    else {
      auto mesh = dbss::read_mesh(name);
      if (!mesh.ok()) return std::fprintf(stderr, "crease_rise_probe: %s\n", mesh.status().to_string().c_str()), 1;
      truth = std::move(mesh).value();
    }
    const double diag = diagonal(truth);
    const std::vector<double> sampled = dbss::sample_surface(truth, points, seed);
    dbss::PointCloud pc;
    pc.xyz.assign(sampled.begin(), sampled.end());
    const dbss::PointIndex index(pc);
    dbss::EncodeOptions eo;
    eo.levels = levels;
    eo.creases.angle_degrees = 30;
    auto e = dbss::encode_points(index, eo);
    if (!e.ok()) return std::fprintf(stderr, "crease_rise_probe: %s\n", e.status().to_string().c_str()), 1;
    const dbss::Encoding& enc = e.value();
    const dbss::format::Creases& creases = enc.contents.creases;
    const dbss::TriangleTree tree(truth);
    const float step = enc.step;

    // Level 0's edges classed.
    const dbss::TriangleMesh& control = enc.control;
    auto topo = dbss::build_topology(static_cast<uint32_t>(control.vertex_count()), control.triangles).value();
    std::vector<uint32_t> crease_count(control.vertex_count(), 0);
    if (!creases.empty())
      for (uint32_t k = 0; k < topo.edge_count(); ++k)
        if (creases.edge[k]) {
          const uint32_t h = topo.edge_half[k];
          ++crease_count[topo.triangles[h]], ++crease_count[topo.triangles[dbss::next_half(h)]];
        }
    const auto corner = [&](uint32_t v) { return !creases.empty() && creases.corner[v] != 0; };
    const auto sharp = [&](uint32_t v) { return crease_count[v] > 0 || corner(v); };
    const auto dart = [&](uint32_t v) { return crease_count[v] == 1 && !corner(v); };
    std::vector<int> cls(at_level == 1 && !bins ? topo.edge_count() : 0);
    for (uint32_t k = 0; k < cls.size(); ++k) {
      const uint32_t h = topo.edge_half[k], u = topo.triangles[h], w = topo.triangles[dbss::next_half(h)];
      if (!creases.empty() && creases.edge[k]) cls[k] = kCrease;
      else if (dart(u) || dart(w)) cls[k] = kDart;
      else if (sharp(u) && sharp(w)) cls[k] = kBridge;
      else if (sharp(u) || sharp(w)) cls[k] = kSide;
      else cls[k] = kSmooth;
    }

    // The sampler as encode_levels sets it up (levels.cpp).
    std::vector<float> normals;
    dbss::PointSides sides;
    dbss::CreaseLines lines;
    if (!creases.empty()) {
      normals = dbss::estimate_point_normals(index, 2);
      sides = {&normals, std::cos(30 * 3.14159265358979323846 / 180), true};
      lines = dbss::CreaseLines(control, creases, index, 2.0, 32);
      if (!lines.empty()) sides.lines = &lines;
    }
    // The stencil points and normals of level 1, and the truth's hit.
    auto refiner = dbss::LevelRefiner::create(control, creases).value();
    for (uint32_t l = 1; l < at_level; ++l) {
      const std::vector<int32_t>& stored = enc.levels.levels[l - 1].q;
      std::vector<int32_t> q;
      refiner.refine([&](uint32_t k, const double*, const double*, const float*, const float*) { return stored[k]; },
                     enc.levels.levels[l - 1].step, q, 2);
    }
    const std::vector<float> parent(refiner.positions().begin(), refiner.positions().end());
    const std::vector<uint32_t> parent_triangles(refiner.triangles().begin(), refiner.triangles().end());
    if (parent != enc.levels.positions[at_level - 1]) return std::fprintf(stderr, "crease_rise_probe: level %u differs from the encoder's\n", at_level - 1), 1;
    std::vector<Odd> odd(refiner.next_odd_count());
    std::vector<int32_t> zero;
    refiner.refine(
        [&](uint32_t k, const double p[3], const double n[3], const float* a, const float* b) {
          Odd& o = odd[k];
          for (int c = 0; c < 3; ++c) o.p[c] = p[c], o.n[c] = n[c];
          const double len = std::sqrt(std::pow(a[0] - b[0], 2.0) + std::pow(a[1] - b[1], 2.0) + std::pow(a[2] - b[2], 2.0));
          o.hit = tree.nearest_line_hit(p, n, 0.5 * len, o.t);
          thread_local dbss::SampleScratch scratch;
          o.s = dbss::sample_displacement(index, p, n, 0.5 * len, 0.5 * len, scratch, true, sides.normals ? &sides : nullptr, false);
          return int32_t{0};
        },
        step, zero, 2);
    // The true feature lines, for the bins.
    std::vector<std::array<uint32_t, 2>> lines_true;
    {
      const dbss::format::Creases tc = dbss::test::creases_from_dihedral(truth, 30);
      auto tt = dbss::build_topology(static_cast<uint32_t>(truth.vertex_count()), truth.triangles).value();
      for (uint32_t k = 0; k < tt.edge_count(); ++k)
        if (tc.edge[k]) lines_true.push_back({tt.triangles[tt.edge_half[k]], tt.triangles[dbss::next_half(tt.edge_half[k])]});
    }
    const bool by_edge = !cls.empty();
    const int classes = by_edge ? kClasses : 4;
    const char* const* class_name = by_edge ? kClassName : kBinName;
    if (!by_edge) {
      cls.resize(odd.size());
      for (size_t k = 0; k < odd.size(); ++k) {
        double d = INFINITY;
        for (const auto& e : lines_true) d = std::min(d, segment_distance(odd[k].p, &truth.positions[3 * size_t{e[0]}], &truth.positions[3 * size_t{e[1]}]));
        int b = 0;
        while (d / diag >= kBin[b]) ++b;
        cls[k] = b;
      }
    }
    const std::vector<float>& l1 = enc.levels.positions[at_level];
    const size_t even = parent.size() / 3;
    double count[kClasses] = {}, stencil[kClasses] = {}, actual[kClasses] = {}, oracle[kClasses] = {}, best[kClasses] = {},
           differ[kClasses] = {}, total = 0;
    const auto at = [&](const Odd& o, double t) {
      const double x[3] = {o.p[0] + t * o.n[0], o.p[1] + t * o.n[1], o.p[2] + t * o.n[2]};
      return tree.distance(x);
    };
    for (size_t k = 0; k < odd.size(); ++k) {
      const Odd& o = odd[k];
      const float* v = &l1[3 * (even + k)];
      const double x[3] = {v[0], v[1], v[2]};
      const double d = tree.distance(x);
      const double moved = (x[0] - o.p[0]) * o.n[0] + (x[1] - o.p[1]) * o.n[1] + (x[2] - o.p[2]) * o.n[2];
      const long q = std::lround(moved / step);
      const long qo = o.hit ? std::lround(o.t / step) : 0;
      double b = INFINITY;
      for (long j = qo - 4; j <= qo + 4; ++j) b = std::min(b, at(o, double(j) * step));
      const int c = cls[k];
      count[c] += 1, stencil[c] += at(o, 0), actual[c] += d, oracle[c] += at(o, double(qo) * step), best[c] += b;
      differ[c] += q != qo;
      total += d;
    }
    if (const char* one = std::getenv("PROBE_ODD")) {
      const Odd& o = odd[std::strtoul(one, nullptr, 10)];
      const float q[3] = {float(o.p[0]), float(o.p[1]), float(o.p[2])};
      uint32_t idx[32];
      float d2[32];
      const size_t f = index.nearest_k(q, 32, idx, d2);
      for (size_t j = 0; j < f; ++j)
        std::printf("pt %.5f %.5f %.5f  nrm %.3f %.3f %.3f\n", pc.xyz[3 * idx[j]], pc.xyz[3 * idx[j] + 1], pc.xyz[3 * idx[j] + 2],
                    normals[3 * idx[j]], normals[3 * idx[j] + 1], normals[3 * idx[j] + 2]);
    }
    // The points' samples against the truth's hit, by class and by what
    // found them (wedge, triangle, plane, nearest; fitted or not).
    {
      constexpr int kSources = 5;
      const char* kSource[] = {"wedge", "triangle", "plane", "nearest", "no truth hit"};
      double n_[kClasses][kSources] = {}, err[kClasses][kSources] = {}, fit[kClasses][kSources] = {};
      for (size_t k = 0; k < odd.size(); ++k) {
        const Odd& o = odd[k];
        const int src = !o.hit ? 4 : o.s.wedge ? 0 : o.s.source == dbss::SampleSource::triangle ? 1 : o.s.source == dbss::SampleSource::plane ? 2 : 3;
        n_[cls[k]][src] += 1, fit[cls[k]][src] += o.s.fitted;
        if (o.hit) err[cls[k]][src] += std::abs(o.s.distance - o.t);
        if (std::getenv("PROBE_DUMP") && o.hit && std::abs(o.s.distance - o.t) > std::atof(std::getenv("PROBE_MIN") ? std::getenv("PROBE_MIN") : "1e-3") * diag && cls[k] == std::atoi(std::getenv("PROBE_DUMP")))
          std::printf("odd %zu src %d p %.5f %.5f %.5f n %.4f %.4f %.4f truth %.5f sample %.5f\n", k, src, o.p[0], o.p[1], o.p[2], o.n[0], o.n[1], o.n[2], o.t, o.s.distance);
      }
      std::printf("## %s (seed %u): level-%u samples against the truth's hit along the normal (mean |sample - truth| / diagonal)\n\n", name.c_str(), seed, at_level);
      std::printf("| class | source | samples | fitted | mean error |\n|---|---|---|---|---|\n");
      for (int c = 0; c < classes; ++c)
        for (int src = 0; src < kSources; ++src)
          if (n_[c][src] > 0)
            std::printf("| %s | %s | %.0f | %.0f | %.2e |\n", class_name[c], kSource[src], n_[c][src], fit[c][src], err[c][src] / n_[c][src] / diag);
      std::printf("\n");
    }
    std::printf("## %s (seed %u): step %.3g of the diagonal; level %u vertex distance to the truth, by %s\n\n", name.c_str(),
                seed, step / diag, at_level, by_edge ? "parent edge" : "distance from a true feature line");
    std::printf("| class | odd | share of sum | stencil | encoded | oracle q | best q | q != oracle's |\n|---|---|---|---|---|---|---|---|\n");
    for (int c = 0; c < classes; ++c) {
      if (count[c] == 0) continue;
      std::printf("| %s | %.0f | %.1f%% | %.2e | %.2e | %.2e | %.2e | %.0f |\n", class_name[c], count[c], 100 * actual[c] / total,
                  stencil[c] / count[c] / diag, actual[c] / count[c] / diag, oracle[c] / count[c] / diag, best[c] / count[c] / diag,
                  differ[c]);
    }
    // Whole levels: the encoder's, and the oracle's sampler with the encoder's
    // step and with one 8 times finer.
    std::printf("\n| variant |");
    for (uint32_t l = 0; l <= levels; ++l) std::printf(" L%u |", l);
    std::printf("\n|---|");
    for (uint32_t l = 0; l <= levels; ++l) std::printf("---|");
    std::printf("\n");
    const dbss::MeshDistanceOptions probe{samples, 1, 2};
    const auto row = [&](const char* what, const dbss::EncodedLevels& out) {
      std::printf("| %s |", what);
      for (uint32_t l = 0; l <= levels; ++l) {
        const dbss::TriangleMesh m{out.positions[l], out.triangles[l]};
        std::printf(" %.3e |", dbss::mesh_distance(m, truth, probe).mean() / diag);
      }
      std::printf("\n");
      std::fflush(stdout);
    };
    row("points (encoded)", enc.levels);
    for (int fine = 0; fine < 2; ++fine) {
      dbss::LevelSampler sampler;
      sampler.sample = [&](uint32_t, const double q[3], const double n[3], double half_length) {
        dbss::Sample s;
        double t = 0;
        if (tree.nearest_line_hit(q, n, half_length, t)) s.distance = t;
        else s.clamped = true;
        return s;
      };
      dbss::LevelEncodeOptions lo;
      lo.levels = levels;
      lo.step = fine ? step / 8 : step;
      lo.threads = 2;
      lo.creases = creases;
      auto out = dbss::encode_levels(control, sampler, lo);
      if (!out.ok()) return std::fprintf(stderr, "crease_rise_probe: %s\n", out.status().to_string().c_str()), 1;
      row(fine ? "oracle, step / 8" : "oracle", out.value());
    }
    std::printf("\n");
  }
  return 0;
}
