// The control mesh's shape against the levels' error: each mesh is sampled
// to points (fixed seed, area-uniform, as rd_bench does), encoded with the
// shaping pass off and on (dbss/encoder/mesh_shape.h), and every level
// decoded from the encoder's reconstruction is compared with the true mesh.
// Prints per shape the control mesh's share of triangles under quality 0.2
// and its largest valence, then per level the bytes, the two-sided mean
// distance and the Hausdorff distance, both over the true mesh's diagonal.
//
// usage: shape_bench [--points N] [--levels L] [--samples S] [--skip-absent]
//                    [--max-bend DEG] [--flip-bend DEG] [--flip-slack S] [--relax-below Q] [--rounds R] MESH_FILE...
//   --max-bend, --flip-bend, --flip-slack, --relax-below, --rounds: the shaping run's ShapeOptions
//   --skip-absent: an absent mesh file exits 77 (ctest's skip) unless CI=true
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "dbss/encoder/encode.h"
#include "dbss/encoder/mesh_shape.h"
#include "dbss/encoder/point_input.h"
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

struct Run {
  dbss::MeshShape shape;
  double seconds = 0;
  std::vector<size_t> bytes;
  std::vector<double> mean, hausdorff;
};

}  // namespace

int main(int argc, char** argv) {
  size_t points = 30000, samples = 200000;
  uint32_t levels = 4;
  std::vector<std::string> meshes;
  bool skip_absent = false;
  dbss::ShapeOptions shaping;  // the "on" run's
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--points" && i + 1 < argc) points = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--levels" && i + 1 < argc) levels = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--samples" && i + 1 < argc) samples = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--skip-absent") skip_absent = true;
    else if (a == "--max-bend" && i + 1 < argc) shaping.max_bend = std::atof(argv[++i]);
    else if (a == "--flip-bend" && i + 1 < argc) shaping.flip_bend = std::atof(argv[++i]);
    else if (a == "--flip-slack" && i + 1 < argc) shaping.flip_slack = std::atof(argv[++i]);
    else if (a == "--relax-below" && i + 1 < argc) shaping.relax_below = std::atof(argv[++i]);
    else if (a == "--rounds" && i + 1 < argc) shaping.rounds = std::atoi(argv[++i]);
    else if (!a.empty() && a[0] == '-') return std::fprintf(stderr, "shape_bench: unknown option %s\n", a.c_str()), 1;
    else meshes.push_back(a);
  }
  if (meshes.empty() || points < 100 || levels > 6 || samples < 2)
    return std::fprintf(stderr, "usage: shape_bench [--points N>=100] [--levels 0..6] [--samples S] MESH_FILE...\n"), 1;
  const char* ci = std::getenv("CI");
  for (const std::string& path : meshes)
    if (skip_absent && !std::filesystem::exists(path) && !(ci != nullptr && std::string(ci) == "true"))
      return std::fprintf(stderr, "shape_bench: %s absent (scripts/fetch-test-data.sh): skipped\n", path.c_str()), 77;
  std::printf("%zu points per shape; error: two-sided mean / Hausdorff distance to the true mesh over its diagonal\n\n",
              points);
  for (const std::string& path : meshes) {
    auto mesh = dbss::read_mesh(path);
    if (!mesh.ok()) return std::fprintf(stderr, "shape_bench: %s\n", mesh.status().to_string().c_str()), 1;
    const dbss::TriangleMesh& truth = mesh.value();
    const double diag = diagonal(truth);
    const std::string shape = std::filesystem::path(path).stem().string();
    const std::vector<double> p = dbss::sample_surface(truth, points, 1);
    dbss::PointCloud pc;
    pc.xyz.assign(p.begin(), p.end());
    if (dbss::Status s = dbss::check_reconstructible(pc, shape); !s.ok())
      return std::fprintf(stderr, "shape_bench: %s\n", s.to_string().c_str()), 1;
    Run runs[2];
    for (int on = 0; on < 2; ++on) {
      dbss::EncodeOptions eo;
      eo.levels = levels;
      eo.control.shape = shaping;
      eo.control.shape.enabled = on == 1;
      const auto t0 = std::chrono::steady_clock::now();
      auto e = dbss::encode_points(pc, eo);
      runs[on].seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (!e.ok()) return std::fprintf(stderr, "shape_bench: %s: %s\n", shape.c_str(), e.status().to_string().c_str()), 1;
      const dbss::Encoding& enc = e.value();
      runs[on].shape = dbss::mesh_shape(enc.control);
      for (uint32_t l = 0; l <= enc.level_count; ++l) {
        const dbss::TriangleMesh m{enc.levels.positions[l], enc.levels.triangles[l]};
        const dbss::MeshDistance d = dbss::mesh_distance(m, truth, {samples, 1, 2});
        runs[on].bytes.push_back(dbss::prefix_bytes(enc, l));
        runs[on].mean.push_back(d.mean() / diag);
        runs[on].hausdorff.push_back(d.max() / diag);
      }
    }
    std::printf("### %s\n", shape.c_str());
    std::printf("control mesh: quality < 0.2 %.1f%% -> %.1f%%, max valence %u -> %u, encode %.1f s -> %.1f s\n\n",
                100 * runs[0].shape.poor_share, 100 * runs[1].shape.poor_share, runs[0].shape.max_valence,
                runs[1].shape.max_valence, runs[0].seconds, runs[1].seconds);
    std::printf("| level | bytes off | bytes on | error off | error on | Hausdorff off | Hausdorff on |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (size_t l = 0; l < std::min(runs[0].bytes.size(), runs[1].bytes.size()); ++l)
      std::printf("| %zu | %zu | %zu | %.3e | %.3e | %.2f%% | %.2f%% |\n", l, runs[0].bytes[l], runs[1].bytes[l],
                  runs[0].mean[l], runs[1].mean[l], 100 * runs[0].hausdorff[l], 100 * runs[1].hausdorff[l]);
    std::printf("\n");
    std::fflush(stdout);
  }
  return 0;
}
