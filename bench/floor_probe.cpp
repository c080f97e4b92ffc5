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
// usage: floor_probe [--points N] [--noise F] [--levels L] [--samples S]
//                    [--variants a,b,...] MESH_FILE...
#include <algorithm>
#include <cmath>
#include <mutex>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
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

}  // namespace

int main(int argc, char** argv) {
  size_t points = 30000, samples = 100000;
  double noise = 0;
  uint32_t levels = 5;
  std::vector<std::string> variants = {"points", "no-dz", "fine", "oracle", "oracle-fine"};
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--points" && i + 1 < argc) points = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--noise" && i + 1 < argc) noise = std::atof(argv[++i]);
    else if (a == "--levels" && i + 1 < argc) levels = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--samples" && i + 1 < argc) samples = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--variants" && i + 1 < argc) variants = split(argv[++i]);
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
    const std::vector<double> p = dbss::sample_surface(truth, points, 1);
    std::mt19937 rng(1 + 1000);
    dbss::PointCloud pc;
    for (double x : p) pc.xyz.push_back(static_cast<float>(noise > 0 ? x + noise * diag * dbss::standard_normal(rng) : x));
    const dbss::PointIndex index(pc);
    dbss::EncodeOptions eo;
    eo.levels = 0;
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
    for (const std::string& v : variants) {
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
        sampler.sample = [&, fit, widen](uint32_t, const double q[3], const double n[3], double half_length) {
          thread_local dbss::SampleScratch scratch;
          const dbss::Sample s = dbss::sample_displacement(index, q, n, half_length, half_length, scratch, fit, nullptr, widen);
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
      std::fflush(stdout);
    }
  }
  return 0;
}
