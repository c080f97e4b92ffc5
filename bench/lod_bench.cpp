// LOD asset storage (issue 18): dbss encoded from a mesh against Draco on
// the same mesh, and one .dbss against a meshoptimizer LOD chain with each
// LOD Draco-compressed at the error dbss reaches at that level.  Every
// error is the two-sided mean distance to the input mesh over its
// bounding-box diagonal (measure/mesh_distance).  Also: dbss's QEM against
// meshoptimizer's simplifier for the control mesh.
//
//   lod_bench [--levels N|auto] [--control-faces F] [--control-bits B] [--cut-holes H] [--hole-radius R] [--cut-only] [--loop-faces N] [--hole-tolerance T] [--hole-faces-per-vertex C] [--errors E1,E2,..] [--samples N] [--detail] [--quick] [--no-search] [--qps A..B] [--dense-step-ratio R] [--plain-rounding] [--control-grid S] [--no-boundary-values] [--fixed-control] [--floor-ratio R] [--bdry-levels MASK] [--bdry-always] [--rdo LAMBDA] [--rdo-from LEVEL] [--max-chain-ratio R] [--input-lod-share S] [--skip-absent] MESH...
//
// With no MESH: the libcgal-demo meshes under test-data/ (closed, with
// holes, several components); --cut-holes H adds each mesh again with H
// holes cut in it.  --skip-absent: exit 77 when a mesh is missing.
#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "dbss/decoder/control_mesh.h"
#include "dbss/decoder/progressive.h"
#include "dbss/encoder/encode_mesh.h"
#include "dbss/encoder/hole_budget.h"
#include "dbss/encoder/mesh_info.h"
#include "dbss/encoder/mesh_input.h"
#include "dbss/encoder/simplify.h"
#include "dbss/io/draco_mesh.h"
#include "dbss/io/geometry_files.h"
#include "dbss/measure/mesh_distance.h"
#include "cut_holes.h"
#include "timing.h"

using namespace dbss;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Draco at compression level 7 (speed 3), as the anchors.
constexpr int kDracoSpeed = 3;

struct Args {
  uint32_t levels = 4;  // --levels auto: kAutoLevels, as `dbss encode`'s default (the file's own level count)
  uint32_t control_faces = 0;  // 0: the encoder's default
  int control_bits = 0;        // Draco's position bits for the control mesh; 0: the encoder's (from the step)
  std::vector<double> errors = {1e-4, 3e-5};
  size_t samples = 100000;
  bool skip_absent = false;
  double max_chain_ratio = 0;  // --max-chain-ratio R: exit 1 when the .dbss is over R x the LOD chain (ctest)
  // --input-lod-share S: a level with at least S x the input's triangles
  // gets the input itself as its LOD (a user's chain keeps the input as its
  // finest LOD rather than a simplification of nearly its size).  1: only
  // levels with at least the input's triangles, as before.
  double input_lod_share = 1;
  bool detail = false;  // --detail: where each level's bytes and error go
  bool quick = false;   // --quick: no simplifier comparison, no decode timing (for sweeps)
  bool no_search = false;  // --no-search: the equal-error table on the targets' grid only
  int search_qp_min = 8, search_qp_max = 14;  // --qps A..B: search only these Draco qps (the rest print "not searched")
  double dense_step_ratio = kMeshDenseStepRatio;  // --dense-step-ratio R (1: one step for every level)
  bool round_along_surface = true;  // --plain-rounding: Draco's own rounding of the control mesh
  double control_grid_steps = MeshEncodeOptions{}.control_grid_steps;  // --control-grid S: Draco's grid in steps
  double rdo_lambda = 0;        // --rdo L: RDO quantization with lambda L (squared steps per bit)
  uint32_t rdo_first_level = 1;  // --rdo-from L
  bool fixed_control = false;   // --fixed-control: the default control mesh, no size choice (EncodeOptions::choose_control)
  double floor_ratio = kMeshFloorRatio;  // --floor-ratio R: the size choice's trigger (MeshEncodeOptions::floor_ratio)
  bool boundary_values = true;  // --no-boundary-values: normal displacements only (format 1.2, no BDRY)
  uint32_t boundary_levels = ~0u;  // --bdry-levels MASK: the levels that may carry BDRY (bit l: level l)
  bool boundary_when_pays = true;  // --bdry-always: BDRY wherever a value is non-zero (the first 1.3 encoder)
  uint32_t cut_holes = 0;  // also run each closed mesh with this many holes cut in it
  double hole_radius = 0.04;  // --hole-radius R: the cut holes' radius over the diagonal
  bool cut_only = false;      // --cut-only: with --cut-holes, only the meshes with holes cut
  // The control budget: --loop-faces N, the fourth session's rule
  // (max(default, N per boundary loop)); --hole-tolerance T and
  // --hole-faces-per-vertex C, hole_budget with other constants.
  uint32_t loop_faces = 0;
  double hole_tolerance = kHoleTolerance, hole_faces_per_vertex = kHoleFacesPerVertex;
  std::vector<std::string> meshes;
};

MeshEncodeOptions mesh_options(const Args& a) {
  MeshEncodeOptions m;
  m.dense_step_ratio = a.dense_step_ratio;
  m.round_along_surface = a.round_along_surface;
  m.control_grid_steps = a.control_grid_steps;
  m.boundary_values = a.boundary_values;
  m.boundary_levels = a.boundary_levels;
  m.boundary_when_pays = a.boundary_when_pays;
  m.rdo_lambda = a.rdo_lambda;
  m.rdo_first_level = a.rdo_first_level;
  m.floor_ratio = a.floor_ratio;
  return m;
}

using bench::diagonal;

struct DracoResult {
  int qp = 0;
  size_t bytes = 0;
  double error = 0, encode_s = 0, decode_s = 0;
};

DracoResult draco(const TriangleMesh& m, int qp, const TriangleMesh& input, double diag, const MeshDistanceOptions& mo) {
  DracoResult r;
  r.qp = qp;
  std::vector<uint8_t> bytes;
  r.encode_s = bench::best_seconds([&] { bytes = io::draco_encode(m, {qp, kDracoSpeed}, "LOD").value(); }, 0.2);
  r.bytes = bytes.size();
  TriangleMesh decoded;
  r.decode_s = bench::best_seconds([&] { decoded = decode_control_mesh(bytes, 1u << 30, 1u << 30).value(); }, 0.2);
  r.error = mesh_distance(decoded, input, mo).mean() / diag;
  return r;
}

TriangleMesh meshopt(const TriangleMesh& m, size_t target_faces, unsigned options) {
  std::vector<uint32_t> out(m.triangles.size());
  const size_t n = meshopt_simplify(out.data(), m.triangles.data(), m.triangles.size(), m.positions.data(), m.vertex_count(),
                                    3 * sizeof(float), 3 * target_faces, 1.0f, options, nullptr);
  out.resize(n);
  // Keep only the vertices still used, as a file would.
  TriangleMesh r;
  std::vector<uint32_t> remap(m.vertex_count(), ~0u);
  for (uint32_t& v : out) {
    if (remap[v] == ~0u) {
      remap[v] = static_cast<uint32_t>(r.vertex_count());
      r.positions.insert(r.positions.end(), m.positions.begin() + 3 * v, m.positions.begin() + 3 * v + 3);
    }
    v = remap[v];
  }
  r.triangles = std::move(out);
  return r;
}

std::string topo(const MeshInfo& i) {
  if (!i.manifold) return "not manifold";
  return std::to_string(i.components) + " cc, genus " + std::to_string(i.genus) + ", " + std::to_string(i.boundary_loops) + " loops";
}

using bench::cut_holes;

// Where a level's bytes and error go: its LEVL bytes per odd vertex, the
// share of zeros and of |q| = 1, the clamps and the casts that missed (the
// closest point instead of a hit on the normal line), and the error in each
// direction (input to level: detail the level lacks; level to input: where
// the level strays off the surface), both over the diagonal.
void print_detail(const Encoding& en, const TriangleMesh& input, double diag, const MeshDistanceOptions& mo) {
  std::printf("\n| level | odd | step / diag | LEVL bytes | coding | bits / odd | zeros | abs(q) = 1 | clamped | cast missed | RDO lowered | input to level | level to input | max |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (uint32_t l = 1; l <= en.level_count; ++l) {
    const LevelStats& st = en.levels.stats[l - 1];
    const auto& q = en.levels.levels[l - 1].q;
    size_t zeros = 0, ones = 0;
    for (int32_t v : q) zeros += v == 0, ones += v == 1 || v == -1;
    const TriangleMesh m{en.levels.positions[l], en.levels.triangles[l]};
    const MeshDistance d = mesh_distance(input, m, mo);
    const double n = st.odd ? double(st.odd) : 1.0;
    std::printf("| %u | %zu | %.2e | %zu | %d | %.2f | %.0f%% | %.0f%% | %zu | %zu | %zu | %.2e | %.2e | %.2e |\n", l, st.odd,
                st.step / diag, st.bytes, static_cast<int>(en.contents.levels[l - 1].coding), 8.0 * st.bytes / n, 100 * zeros / n, 100 * ones / n, st.clamped, st.by_nearest, st.rdo_lowered,
                d.a_to_b_mean / diag, d.b_to_a_mean / diag, d.max() / diag);
  }
}

// The search stops once a level's error is within this share under the
// Draco error it is matched against (or the targets bracketing it are this
// close).
constexpr double kSearchTolerance = 0.02;

// dbss's (prefix bytes, error) per level as a function of the error target,
// encoded on demand and remembered: the equal-error search bisects it.
class TargetCurve {
 public:
  struct Point {
    std::vector<uint64_t> prefix;  // per level
    std::vector<double> error;     // per level, over the diagonal
  };
  struct Found {
    double target;
    uint32_t level;
    uint64_t prefix;
    double error;
  };

  TargetCurve(const TriangleMesh& input, const Args& args, double diag, const MeshDistanceOptions& mo)
      : input_(input), args_(args), diag_(diag), mo_(mo) {}

  // A level measured elsewhere (the grid's encodings).
  void seed(double target, uint32_t level, uint64_t prefix, double error) {
    Point& p = points_[target];
    levels_ = std::max(levels_, level);
    if (p.prefix.size() <= level) p.prefix.resize(level + 1, 0), p.error.resize(level + 1, 0);
    p.prefix[level] = prefix;
    p.error[level] = error;
  }

  // The smallest prefix over all levels whose error is at most `want`,
  // each level's target bisected (in log target) until its error is within
  // kSearchTolerance under `want`; none when no level reaches it.
  std::optional<Found> smallest_prefix_at(double want) {
    std::optional<Found> best;
    for (uint32_t l = 0; l <= levels_; ++l) {
      // Levels whose error does not depend on the target (the control
      // mesh's rounding aside) still count: level 0 is read off as is.
      double lo = 0, hi = 0;  // lo: largest target with error <= want; hi: smallest above lo with error > want
      for (int it = 0; it < 24; ++it) {
        bracket(l, want, lo, hi);
        if (lo > 0 && best && hi > 0 && points_[hi].prefix[l] >= best->prefix) break;  // cannot beat it
        double next = 0;
        if (lo == 0) {
          // Nothing reaches `want` yet: finer, down to a target an eighth
          // of it (below that the level's floor is not the rounding).
          const double finest = points_.begin()->first;
          if (finest / 2 < want / 8) break;
          next = finest / 2;
          // A level that did not improve between the two finest targets has hit its floor.
          if (points_.size() >= 2) {
            auto a = points_.begin(), b = std::next(a);
            if (a->second.error.size() > l && b->second.error.size() > l && a->second.error[l] > want &&
                a->second.error[l] >= 0.97 * b->second.error[l])
              break;
          }
        } else if (hi == 0) {
          // Everything measured reaches it: coarser, up to 16 times `want`.
          const double coarsest = points_.rbegin()->first;
          if (coarsest * 2 > 16 * want) break;
          next = coarsest * 2;
        } else {
          const double elo = points_[lo].error[l], ehi = points_[hi].error[l];
          if (elo >= (1 - kSearchTolerance) * want || hi / lo < 1 + kSearchTolerance) break;
          // Log-log interpolation of the error between the bracket, kept
          // off its ends so a bend in the curve cannot stall the search.
          double f = 0.5;
          if (elo > 0 && ehi > elo) f = std::clamp(std::log(want / elo) / std::log(ehi / elo), 0.2, 0.8);
          next = lo * std::pow(hi / lo, f);
        }
        if (!measure(next)) break;
      }
      bracket(l, want, lo, hi);
      if (lo == 0) continue;
      const Point& p = points_[lo];
      if (!best || p.prefix[l] < best->prefix) best = Found{lo, l, p.prefix[l], p.error[l]};
    }
    return best;
  }

  size_t encodings() const { return encodings_; }
  // Of them: with a larger control candidate encoded (floor-bound), and with it kept.
  size_t candidates() const { return candidates_; }
  size_t larger() const { return larger_; }
  double seconds() const { return seconds_; }

 private:
  // Targets measured at level l (every level up to args_.levels once encoded here).
  void bracket(uint32_t l, double want, double& lo, double& hi) {
    lo = hi = 0;
    for (const auto& [t, p] : points_) {
      if (p.error.size() <= l || p.prefix[l] == 0) continue;
      if (p.error[l] <= want) lo = t;
    }
    for (const auto& [t, p] : points_) {
      if (p.error.size() <= l || p.prefix[l] == 0) continue;
      if (t > lo && p.error[l] > want) {
        hi = t;
        break;
      }
    }
  }

  bool measure(double target) {
    // (With --levels auto each encoding has its own level count: a target
    // seen with every level it has is known.)
    if (auto it = points_.find(target); it != points_.end() && !it->second.prefix.empty() &&
                                        std::find(it->second.prefix.begin(), it->second.prefix.end(), 0) == it->second.prefix.end())
      return false;  // already known: the search is not moving
    const auto t0 = Clock::now();
    EncodeOptions o;
    o.levels = args_.levels;
    o.control.control_faces = args_.control_faces;
    o.control_bits = args_.control_bits;
    o.error = target;
    o.threads = 2;
    o.choose_control = !args_.fixed_control;
    auto e = encode_mesh(input_, o, mesh_options(args_));
    if (!e.ok()) return false;
    const Encoding& en = e.value().encoding;
    const std::string& choice = en.control_choice;
    candidates_ += choice.find("floor-bound") != std::string::npos && choice.find("not floor-bound") == std::string::npos;
    larger_ += choice.rfind("kept the larger", 0) == 0;
    Point p;
    for (uint32_t l = 0; l <= en.level_count; ++l) {
      const TriangleMesh m{en.levels.positions[l], en.levels.triangles[l]};
      p.prefix.push_back(prefix_bytes(en, l));
      p.error.push_back(mesh_distance(m, input_, mo_).mean() / diag_);
    }
    levels_ = std::max(levels_, en.level_count);
    points_[target] = std::move(p);
    ++encodings_;
    seconds_ += since(t0);
    return true;
  }

  const TriangleMesh& input_;
  const Args& args_;
  double diag_;
  MeshDistanceOptions mo_;
  std::map<double, Point> points_;
  uint32_t levels_ = 0;  // the most levels any encoding had (with --levels auto they differ)
  size_t encodings_ = 0, candidates_ = 0, larger_ = 0;
  double seconds_ = 0;
};

int run_mesh(const std::string& path, Args args, uint32_t holes = 0) {
  auto read = read_mesh(path);
  if (!read.ok()) {
    std::fprintf(stderr, "lod_bench: %s\n", read.status().message().c_str());
    return 1;
  }
  if (holes) read.value() = cut_holes(read.value(), holes, args.hole_radius);
  auto prepared = prepare_mesh_input(read.value());
  if (!prepared.ok()) {
    std::fprintf(stderr, "lod_bench: %s: %s\n", path.c_str(), prepared.status().message().c_str());
    return 1;
  }
  const TriangleMesh input = std::move(prepared).value();
  const MeshInfo info = mesh_info(input);
  const double diag = diagonal(input);
  MeshDistanceOptions mo;
  mo.samples = args.samples;
  mo.threads = 2;
  const std::string name = std::filesystem::path(path).filename().string() +
                           (holes ? " with " + std::to_string(holes) + " holes cut" : std::string());
  std::printf("\n## %s: %zu vertices, %zu triangles, %s\n", name.c_str(), input.vertex_count(), input.triangle_count(),
              topo(info).c_str());

  // The control mesh's simplifier: dbss's QEM against meshoptimizer's.
  const HoleBudget budget = hole_budget(input, info.genus, args.hole_tolerance, args.hole_faces_per_vertex);
  if (!args.control_faces && args.loop_faces)
    args.control_faces = std::max<uint32_t>(default_control_faces(static_cast<uint32_t>(input.triangle_count()), info.genus),
                                            args.loop_faces * info.boundary_loops) & ~1u;
  else if (!args.control_faces && budget.faces != mesh_control_faces(input, info.genus))
    args.control_faces = budget.faces;
  const uint32_t target = args.control_faces ? args.control_faces : mesh_control_faces(input, info.genus);
  std::printf("\ncontrol budget: %u faces (closed budget %u, its edge %.2e of the diagonal; %zu loops", target,
              budget.closed_faces, budget.edge_length / diag, budget.loop_vertices.size());
  if (!budget.loop_vertices.empty()) {
    uint64_t sum = 0;
    uint32_t most = 0;
    for (uint32_t n : budget.loop_vertices) sum += n, most = std::max(most, n);
    std::printf(", rim vertices needed %llu, at most %u a loop", static_cast<unsigned long long>(sum), most);
  }
  std::printf(")\n");
  if (!args.quick) {
  std::printf("\ncontrol mesh simplifier, target %u triangles:\n\n", target);
  std::printf("| simplifier | ms | triangles | topology | error |\n|---|---|---|---|---|\n");
  {
    auto t = Clock::now();
    const TriangleMesh q = simplify_mesh(input, target).value();
    const double s = since(t);
    std::printf("| dbss QEM (simplify_mesh) | %.0f | %zu | %s | %.2e |\n", 1e3 * s, q.triangle_count(), topo(mesh_info(q)).c_str(),
                mesh_distance(q, input, mo).mean() / diag);
    for (unsigned opt : {0u, unsigned(meshopt_SimplifyLockBorder)}) {
      t = Clock::now();
      const TriangleMesh m = meshopt(input, target, opt);
      const double ms = since(t);
      std::printf("| meshopt_simplify%s | %.0f | %zu | %s | %.2e |\n", opt ? " (lock border)" : "", 1e3 * ms, m.triangle_count(),
                  topo(mesh_info(m)).c_str(), mesh_distance(m, input, mo).mean() / diag);
    }
  }
  }

  // Draco on the input.
  std::printf("\nDraco (cl7) on the input mesh:\n\n| qp | bytes | error | encode ms | decode ms |\n|---|---|---|---|---|\n");
  std::vector<DracoResult> dr;
  for (int qp = 8; qp <= 14; ++qp) {
    dr.push_back(draco(input, qp, input, diag, mo));
    const DracoResult& r = dr.back();
    std::printf("| %d | %zu | %.2e | %.1f | %.1f |\n", qp, r.bytes, r.error, 1e3 * r.encode_s, 1e3 * r.decode_s);
  }

  // dbss from the mesh, at each error target: per level prefix bytes, error, decode time.
  struct Row {
    double target;
    uint32_t level;
    size_t triangles;
    uint64_t prefix;
    double error, decode_s;
  };
  std::vector<Row> rows;
  std::vector<MeshEncoding> encodings;
  for (double err : args.errors) {
    EncodeOptions o;
    o.levels = args.levels;
    o.control.control_faces = args.control_faces;
    o.control_bits = args.control_bits;
    o.error = err;
    o.threads = 2;
    o.choose_control = !args.fixed_control;
    auto t = Clock::now();
    auto e = encode_mesh(input, o, mesh_options(args));
    const double enc_s = since(t);
    if (!e.ok()) {
      std::fprintf(stderr, "lod_bench: %s: %s\n", path.c_str(), e.status().to_string().c_str());
      return 1;
    }
    const Encoding& en = e.value().encoding;
    std::printf("\ndbss from the mesh, error target %g: encode %.2f s (QEM %.2f s, casting %.2f s), %zu bytes, %u levels%s\n\n", err,
                enc_s, en.seconds.control, en.seconds.levels, en.bytes.size(), en.level_count,
                args.levels == kAutoLevels ? " (auto)" : "");
    {
      const format::Header& h = en.contents.header;
      const format::MeshCounts control{h.control_vertex_count, h.control_edge_count, h.control_triangle_count};
      // `dbss encode`'s default (auto_levels: the first level with more
      // vertices than the input), beside the first level with the input's
      // triangles, the count the chain below stores the input for.
      uint32_t by_triangles = 1;
      while (by_triangles < format::kMaxLevelsInPractice && format::counts_at_level(control, by_triangles) &&
             format::counts_at_level(control, by_triangles)->triangles < input.triangle_count())
        ++by_triangles;
      std::printf("auto levels here: %u (first level with more vertices than the input; with at least its triangles: %u)\n\n",
                  auto_levels(control, input.vertex_count()), by_triangles);
    }
    if (!en.control_choice.empty()) std::printf("control choice (%.2f s): %s\n\n", en.seconds.choice, en.control_choice.c_str());
    std::printf("| level | triangles | prefix bytes | error | decode ms (levels 0..l) |\n|---|---|---|---|---|\n");
    for (uint32_t l = 0; l <= en.level_count; ++l) {
      const TriangleMesh m{en.levels.positions[l], en.levels.triangles[l]};
      Row r{err, l, m.triangle_count(), prefix_bytes(en, l), mesh_distance(m, input, mo).mean() / diag, 0};
      if (!args.quick) r.decode_s = bench::best_seconds([&] { (void)decode_bytes(en.bytes, static_cast<int>(l)); }, 0.3);
      std::printf("| %u | %zu | %llu | %.2e | %.1f |\n", l, r.triangles, static_cast<unsigned long long>(r.prefix), r.error,
                  1e3 * r.decode_s);
      rows.push_back(r);
    }
    if (args.detail) print_detail(en, input, diag, mo);
    encodings.push_back(std::move(e).value());
  }

  // Equal error on the error targets' grid: the smallest dbss prefix at or
  // under each Draco error among the targets given.  Kept beside the search
  // below, which it overstates (a sparse grid lands under Draco's error by
  // up to a grid step).
  std::vector<double> grid_ratio(dr.size(), 0);
  std::printf("\nequal error on the grid of targets (smallest dbss prefix with error <= Draco's):\n\n");
  std::printf("| Draco qp | Draco bytes | Draco error | dbss prefix | its error | (target, level) | dbss / Draco |\n|---|---|---|---|---|---|---|\n");
  for (size_t k = 0; k < dr.size(); ++k) {
    const DracoResult& d = dr[k];
    const Row* best = nullptr;
    for (const Row& r : rows)
      if (r.error <= d.error && (!best || r.prefix < best->prefix)) best = &r;
    if (!best) {
      std::printf("| %d | %zu | %.2e | - | - | - | not reached |\n", d.qp, d.bytes, d.error);
      continue;
    }
    grid_ratio[k] = double(best->prefix) / d.bytes;
    std::printf("| %d | %zu | %.2e | %llu | %.2e | (%g, %u) | %.2f |\n", d.qp, d.bytes, d.error,
                static_cast<unsigned long long>(best->prefix), best->error, best->target, best->level, grid_ratio[k]);
  }

  // Equal error by search: per Draco qp and per level, the error target is
  // bisected until that level's error lands just under Draco's.
  if (!args.no_search) {
    TargetCurve curve(input, args, diag, mo);
    for (const Row& r : rows) curve.seed(r.target, r.level, r.prefix, r.error);
    std::printf("\nequal error by search (per qp and level, the error target bisected until the level's error is within %.0f%% under Draco's):\n\n",
                100 * kSearchTolerance);
    std::printf("| Draco qp | Draco bytes | Draco error | dbss prefix | its error | (target, level) | dbss / Draco | on the grid |\n"
                "|---|---|---|---|---|---|---|---|\n");
    for (size_t k = 0; k < dr.size(); ++k) {
      const DracoResult& d = dr[k];
      const char* grid = nullptr;
      char grid_text[32];
      if (grid_ratio[k] > 0) std::snprintf(grid_text, sizeof grid_text, "%.2f", grid_ratio[k]), grid = grid_text;
      if (d.qp < args.search_qp_min || d.qp > args.search_qp_max) {
        std::printf("| %d | %zu | %.2e | - | - | - | not searched | %s |\n", d.qp, d.bytes, d.error, grid ? grid : "not reached");
        continue;
      }
      const auto best = curve.smallest_prefix_at(d.error);
      if (!best) {
        std::printf("| %d | %zu | %.2e | - | - | - | not reached | %s |\n", d.qp, d.bytes, d.error, grid ? grid : "not reached");
        continue;
      }
      std::printf("| %d | %zu | %.2e | %llu | %.2e | (%.3g, %u) | %.2f | %s |\n", d.qp, d.bytes, d.error,
                  static_cast<unsigned long long>(best->prefix), best->error, best->target, best->level,
                  double(best->prefix) / d.bytes, grid ? grid : "not reached");
    }
    std::printf("\nsearch: %zu encodings (%zu with a larger control candidate, %zu kept it), %.1f s encoding and measuring\n",
                curve.encodings(), curve.candidates(), curve.larger(), curve.seconds());
  }

  // One .dbss (the first error target) against a meshoptimizer LOD chain of
  // the same triangle counts, each LOD Draco-compressed at the coarsest qp
  // whose error is at or under dbss's at that level.
  const Encoding& en = encodings.front().encoding;
  std::printf("\none .dbss (error target %g) vs a meshoptimizer LOD chain + Draco at matching error:\n\n", args.errors.front());
  std::printf("| level | triangles | dbss error | LOD triangles | LOD qp | LOD error | LOD bytes | dbss decode ms (0..l) | Draco decode ms |\n|---|---|---|---|---|---|---|---|---|\n");
  // Levels with at least the input's triangles get the input itself as
  // their LOD: it is stored once, at the qp the strictest of them needs.
  size_t chain = 0, input_lod = 0;
  bool all_matched = true;
  for (uint32_t l = 0; l <= en.level_count; ++l) {
    const Row& r = rows[l];
    const bool is_input = double(r.triangles) >= args.input_lod_share * double(input.triangle_count());
    const TriangleMesh lod = is_input ? input : meshopt(input, r.triangles, 0);
    DracoResult pick;
    bool matched = false;
    for (int qp = 8; qp <= 16 && !matched; ++qp) {
      pick = draco(lod, qp, input, diag, mo);
      matched = pick.error <= r.error;
    }
    all_matched = all_matched && matched;
    if (is_input) input_lod = std::max(input_lod, pick.bytes);
    else chain += pick.bytes;
    std::printf("| %u | %zu | %.2e | %zu%s | %d%s | %.2e | %zu | %.1f | %.1f |\n", l, r.triangles, r.error, lod.triangle_count(),
                is_input ? " (the input)" : "", pick.qp, matched ? "" : " (not matched)", pick.error, pick.bytes, 1e3 * r.decode_s,
                1e3 * pick.decode_s);
  }
  chain += input_lod;
  std::printf("\ntotal: .dbss %zu bytes, LOD chain %zu bytes (the input counted once): %.2f x%s\n", en.bytes.size(), chain,
              double(en.bytes.size()) / chain, all_matched ? "" : " (some LODs cannot reach dbss's error at qp 16)");
  if (args.max_chain_ratio > 0 && double(en.bytes.size()) > args.max_chain_ratio * chain) {
    std::fprintf(stderr, "lod_bench: %s: the .dbss is %.2f x the LOD chain, over --max-chain-ratio %g\n", name.c_str(),
                 double(en.bytes.size()) / chain, args.max_chain_ratio);
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--levels" && i + 1 < argc) {
      const std::string v = argv[++i];
      args.levels = v == "auto" ? kAutoLevels : static_cast<uint32_t>(std::atoi(v.c_str()));
    }
    else if (a == "--cut-holes" && i + 1 < argc) args.cut_holes = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--hole-radius" && i + 1 < argc) args.hole_radius = std::atof(argv[++i]);
    else if (a == "--cut-only") args.cut_only = true;
    else if (a == "--loop-faces" && i + 1 < argc) args.loop_faces = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--hole-tolerance" && i + 1 < argc) args.hole_tolerance = std::atof(argv[++i]);
    else if (a == "--hole-faces-per-vertex" && i + 1 < argc) args.hole_faces_per_vertex = std::atof(argv[++i]);
    else if (a == "--control-faces" && i + 1 < argc) args.control_faces = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--samples" && i + 1 < argc) args.samples = static_cast<size_t>(std::atol(argv[++i]));
    else if (a == "--control-bits" && i + 1 < argc) args.control_bits = std::atoi(argv[++i]);
    else if (a == "--detail") args.detail = true;
    else if (a == "--plain-rounding") args.round_along_surface = false;
    else if (a == "--control-grid" && i + 1 < argc) args.control_grid_steps = std::atof(argv[++i]);
    else if (a == "--quick") args.quick = true;
    else if (a == "--no-search") args.no_search = true;
    else if (a == "--qps" && i + 1 < argc) {
      const std::string v = argv[++i];
      const size_t dots = v.find("..");
      args.search_qp_min = std::atoi(v.substr(0, dots).c_str());
      args.search_qp_max = dots == std::string::npos ? args.search_qp_min : std::atoi(v.substr(dots + 2).c_str());
    }
    else if (a == "--no-boundary-values") args.boundary_values = false;
    else if (a == "--fixed-control") args.fixed_control = true;
    else if (a == "--floor-ratio" && i + 1 < argc) args.floor_ratio = std::atof(argv[++i]);
    else if (a == "--bdry-always") args.boundary_when_pays = false;
    else if (a == "--bdry-levels" && i + 1 < argc) args.boundary_levels = static_cast<uint32_t>(std::strtoul(argv[++i], nullptr, 0));
    else if (a == "--rdo" && i + 1 < argc) args.rdo_lambda = std::atof(argv[++i]);
    else if (a == "--rdo-from" && i + 1 < argc) args.rdo_first_level = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--dense-step-ratio" && i + 1 < argc) args.dense_step_ratio = std::atof(argv[++i]);
    else if (a == "--errors" && i + 1 < argc) {
      args.errors.clear();
      std::string s = argv[++i];
      for (size_t p = 0; p <= s.size();) {
        const size_t q = std::min(s.find(',', p), s.size());
        args.errors.push_back(std::atof(s.substr(p, q - p).c_str()));
        p = q + 1;
      }
    } else if (a == "--skip-absent") args.skip_absent = true;
    else if (a == "--max-chain-ratio" && i + 1 < argc) args.max_chain_ratio = std::atof(argv[++i]);
    else if (a == "--input-lod-share" && i + 1 < argc) args.input_lod_share = std::atof(argv[++i]);
    else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "usage: lod_bench [--levels N|auto] [--control-faces F] [--control-bits B] [--cut-holes H] [--hole-radius R] [--cut-only] [--loop-faces N] [--hole-tolerance T] [--hole-faces-per-vertex C] [--errors E1,E2] [--samples N] [--detail] [--quick] [--no-search] [--qps A..B] [--dense-step-ratio R] [--plain-rounding] [--control-grid S] [--no-boundary-values] [--fixed-control] [--floor-ratio R] [--bdry-levels MASK] [--bdry-always] [--rdo LAMBDA] [--rdo-from LEVEL] [--max-chain-ratio R] [--input-lod-share S] [--skip-absent] MESH...\n");
      return 1;
    } else args.meshes.push_back(a);
  }
  if (!(args.input_lod_share > 0 && args.input_lod_share <= 1)) {
    std::fprintf(stderr, "lod_bench: --input-lod-share must be in (0, 1]\n");
    return 1;
  }
  if (args.meshes.empty())
    for (const char* m : {"bunny00.off", "armadillo.off", "elephant-with-holes.off", "blobby_3cc.off"})
      args.meshes.push_back(std::string(DBSS_SOURCE_DIR) + "/test-data/data/meshes/" + m);
  for (const std::string& m : args.meshes)
    if (!std::filesystem::exists(m)) {
      std::fprintf(stderr, "lod_bench: %s: missing%s\n", m.c_str(), args.skip_absent ? " (skipped)" : "");
      return args.skip_absent ? 77 : 1;
    }
  int rc = 0;
  for (const std::string& m : args.meshes) {
    if (!(args.cut_only && args.cut_holes)) rc = std::max(rc, run_mesh(m, args));
    if (args.cut_holes) rc = std::max(rc, run_mesh(m, args, args.cut_holes));
  }
  return rc;
}
