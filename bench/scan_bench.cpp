// Real-scan regression table (issue 13): the encoder with default options on
// defective scans of known shapes (tests/defect_shapes.h: outliers, holes,
// a half, uneven density, noise) and on the libcgal-demo scans when
// scripts/fetch-test-data.sh (or scripts/scan-bench.sh) has unpacked them.
// One row per input: what came out (components, genus, boundary loops of
// the finest level), the share of clamped displacements there, the points'
// mean distance to that surface (relative to the diagonal, and to the
// points' median spacing), the encode time, whether encoding failed, and
// the self-check's warnings.
//
// Built with DBSS_SCAN_CHECK (bench/CMakeLists.txt) it also shows the
// outlier removal, the surface mode chosen and check_scan()'s warnings;
// without it, it builds against the encoder before those existed (the
// "before" table).
//
// usage: scan_bench [--levels L] [--points N] [--no-scans] [--data DIR] [--surface auto|closed|open] [--hole-sweep | --clean | --plates]
//                   [--keep-outliers] [NAME_PART...]
//   --clean: instead of the table, complete scans that must come out right
//   and unwarned: the tori of genus 1-3 at eight seeds, eight.off and
//   3torus.off sampled, and bunny00.off read as points (a false warning or a lost handle shows);
//   --plates: plates with 3-4 round through-holes, and solid plates scanned
//   with gaps in their place (handles that open together at one grid);
//   --points: samples per shape (default 8000); --data: the directory holding
//   data/points_3 and data/meshes (default the source tree's test-data);
//   NAME_PART: run only the inputs whose name contains one of them.
#include <algorithm>
#include <numbers>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <tuple>
#include <vector>

#include "../tests/defect_shapes.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/point_distances.h"
#include "dbss/encoder/point_input.h"
#include "dbss/io/geometry_files.h"
#include "dbss/measure/surface_samples.h"
#ifdef DBSS_SCAN_CHECK
#include "dbss/encoder/outliers.h"
#include "dbss/encoder/scan_check.h"
#endif

namespace {

using dbss::PointCloud;
namespace dt = dbss::test;

// One input: the points given to the encoder, and the points its error is
// measured on (the input without the outliers added to it; else the input).
// `expect`: the right result's components/genus/boundary loops ("1/2/0"),
// alternatives separated by '|' (a hole may be bridged or kept open); empty
// when not known.
struct Input {
  std::string name;
  std::function<std::pair<PointCloud, PointCloud>()> make;  // points, reference
  std::string expect;
};

// The hole sweep's complete scans, by shape name (an input named "<shape>
// ..." was cut from it): the error ratio is measured against their surfaces.
using CompleteScans = std::vector<std::pair<std::string, std::function<PointCloud()>>>;

struct Options {
  uint32_t levels = 2;
  size_t shape_points = 8000;
  bool scans = true;
  std::string data = std::string(DBSS_SOURCE_DIR) + "/test-data";
  std::vector<std::string> only;
  bool hole_sweep = false;
  bool clean = false;
  bool plates = false;
#ifdef DBSS_SCAN_CHECK
  dbss::SurfaceMode surface = dbss::SurfaceMode::automatic;
  bool keep_outliers = false;
#endif
};

std::vector<Input> defect_inputs(const Options& o) {
  std::vector<Input> in;
  const auto shapes = dt::genus_shapes();
  for (const char* name : {"sphere", "torus", "double torus"}) {
    const dt::Shape* s = dt::find_shape(shapes, name);
    if (!s) continue;
    const dt::Shape shape = *s;
    const size_t n = o.shape_points;
    auto clean = [shape, n] { return dt::sample_sdf(shape.sdf, shape.lo, shape.hi, n, 7); };
    const std::string b = name;
    const std::string g = std::to_string(shape.genus);
    const std::string closed = "1/" + g + "/0";
    // Cut by the plane z = 0: a disk with `genus` holes in it.
    const std::string halved = "1/0/" + std::to_string(shape.genus + 1);
    in.push_back({b, [clean] { auto c = clean(); return std::pair{c, c}; }, closed});
    for (double share : {0.005, 0.01})
      in.push_back({b + " +" + (share < 0.0075 ? "0.5" : "1") + "% outliers", [clean, share] {
                      auto c = clean();
                      return std::pair{dt::with_outliers(c, share, 11), c};
                    }, closed});
    for (double share : {0.10, 0.15})
      in.push_back({b + " hole " + (share < 0.125 ? "10" : "15") + "%", [clean, share] {
                      auto h = dt::with_hole(clean(), {0.3, 0.2, 1.0}, share);
                      return std::pair{h, h};
                    }, closed + "|1/" + g + "/1"});
    in.push_back({b + " half", [clean] { auto h = dt::half(clean()); return std::pair{h, h}; }, halved});
    in.push_back({b + " density 10x", [clean] {
                    auto d = dt::with_density_gradient(clean(), 10.0, 13);
                    return std::pair{d, d};
                  }, closed});
    in.push_back({b + " noise 0.1%", [clean] {
                    auto d = dt::with_noise(clean(), 0.001, 17);
                    return std::pair{d, d};
                  }, closed});
  }
  return in;
}

// Holes of 10% and 15% of the area from six directions in the tori of
// genus 1-3, sampled with another seed than the table's: where a hole runs
// right round a tube, closing it keeps the genus only if the two cut ends
// are joined.  Right: closed with the genus, or open along the hole (one
// loop, or two and a handle fewer where the band went round a tube).
std::vector<Input> hole_sweep_inputs(const Options& o, CompleteScans& complete) {
  std::vector<Input> in;
  const auto shapes = dt::genus_shapes();
  const dt::Vec3 directions[] = {{0.3, 0.2, 1.0}, {1, 0, 0}, {0, 1, 0.3}, {-1, 0.5, 0.2}, {0.2, -1, -0.4}, {0, 0, -1}};
  for (const char* name : {"torus", "double torus", "triple torus"}) {
    const dt::Shape* s = dt::find_shape(shapes, name);
    if (!s) continue;
    const dt::Shape shape = *s;
    const size_t n = o.shape_points;
    const long long g = shape.genus;
    complete.emplace_back(name, [shape, n] { return dt::sample_sdf(shape.sdf, shape.lo, shape.hi, n, 5); });
    const std::string expect = "1/" + std::to_string(g) + "/0|1/" + std::to_string(g) + "/1|1/" + std::to_string(g - 1) + "/2";
    for (const dt::Vec3& d : directions)
      for (double share : {0.10, 0.15}) {
        char label[96];
        std::snprintf(label, sizeof label, "%s %.0f%% (%g,%g,%g)", name, 100 * share, d[0], d[1], d[2]);
        in.push_back({label, [shape, n, d, share] {
                        auto h = dt::with_hole(dt::sample_sdf(shape.sdf, shape.lo, shape.hi, n, 5), d, share);
                        return std::pair{h, h};
                      }, expect});
      }
  }
  return in;
}

// Complete scans (--clean): every one must keep its topology with no
// warning.  The tori at eight seeds (a sparse sampling's gaps fall
// differently at each), and three meshes' vertices read as points.
std::vector<Input> clean_inputs(const Options& o) {
  std::vector<Input> in;
  const auto shapes = dt::genus_shapes();
  for (const char* name : {"torus", "double torus", "triple torus"}) {
    const dt::Shape* s = dt::find_shape(shapes, name);
    if (!s) continue;
    const dt::Shape shape = *s;
    const size_t n = o.shape_points;
    for (uint32_t seed : {5u, 7u, 11u, 13u, 17u, 19u, 23u, 29u})
      in.push_back({std::string(name) + " seed " + std::to_string(seed), [shape, n, seed] {
                      auto c = dt::sample_sdf(shape.sdf, shape.lo, shape.hi, n, seed);
                      return std::pair{c, c};
                    }, "1/" + std::to_string(shape.genus) + "/0"});
  }
  // Meshes of known genus: eight.off and 3torus.off are too coarse to read
  // as points (315 and 19 vertices), so their surfaces are sampled with the
  // shapes' count; bunny00.off's 35k vertices are a scan as they are.
  for (const auto& [file, genus, sampled] : {std::tuple{"eight.off", 2, true}, std::tuple{"3torus.off", 3, true},
                                             std::tuple{"bunny00.off", 0, false}}) {
    const std::string p = o.data + "/data/meshes/" + file;
    if (!std::filesystem::exists(p)) {
      std::fprintf(stderr, "scan_bench: %s absent (scripts/fetch-test-data.sh), skipped\n", p.c_str());
      continue;
    }
    const size_t n = o.shape_points;
    const bool sample = sampled;
    in.push_back({std::string(file) + (sample ? " sampled" : ""), [p, n, sample] {
                    PointCloud c;
                    if (sample) {
                      auto m = dbss::read_mesh(p);
                      if (m.ok()) {
                        const std::vector<double> xyz = dbss::sample_surface(m.value(), n, 5);
                        c.xyz.assign(xyz.begin(), xyz.end());
                      }
                    } else if (auto r = dbss::read_points(p); r.ok()) {
                      c = std::move(r).value();
                    }
                    return std::pair{c, c};
                  }, "1/" + std::to_string(genus) + "/0"});
  }
  return in;
}

// Plates with round through-holes (--plates), and the same plates solid but
// scanned with gaps where the holes were: several handles that open at one
// grid of the search (cell_carving.cpp's handles_resolved) must be the real
// holes' only.  Plates 0.08 and 0.2 thick, holes of radius 0.18, seeds 5
// and 7.  Right: the holes' genus; the gaps bridged (genus 0, closed) or
// kept open on both faces (genus 0, two loops a gap).
std::vector<Input> plate_inputs(const Options& o) {
  std::vector<Input> in;
  const size_t n = o.shape_points;
  constexpr double kRadius = 0.18;
  for (double half : {0.04, 0.1})
    for (int holes : {3, 4})
      for (uint32_t seed : {5u, 7u}) {
        char label[96];
        const dt::Shape plate = dt::holed_plate(half, holes, kRadius);
        std::snprintf(label, sizeof label, "plate %.2f %d holes s%u", 2 * half, holes, seed);
        in.push_back({label, [plate, n, seed] {
                        auto c = dt::sample_sdf(plate.sdf, plate.lo, plate.hi, n, seed);
                        return std::pair{c, c};
                      }, "1/" + std::to_string(holes) + "/0"});
        // The holes' walls scanned too, at the faces' density (with_hole_walls).
        std::snprintf(label, sizeof label, "plate %.2f %d walled s%u", 2 * half, holes, seed);
        in.push_back({label, [plate, half, holes, n, seed] {
                        auto c = dt::sample_sdf(plate.sdf, plate.lo, plate.hi, n, seed);
                        const double face_area = 2 * (2 * 2 * 0.7 - holes * kRadius * kRadius * std::numbers::pi);
                        const double wall_area = holes * 2 * std::numbers::pi * kRadius * 2 * half;
                        const size_t wall = static_cast<size_t>(static_cast<double>(n) * wall_area / face_area);
                        c = dt::with_hole_walls(std::move(c), holes, kRadius, half, wall, seed + 1000);
                        return std::pair{c, c};
                      }, "1/" + std::to_string(holes) + "/0"});
        std::snprintf(label, sizeof label, "plate %.2f %d gaps s%u", 2 * half, holes, seed);
        in.push_back({label, [half, holes, n, seed] {
                        // As many points on the solid plate's area as the holed one
                        // keeps: the same density where both have surface.
                        const dt::Sdf solid = [half](double x, double y, double z) { return dt::box_sdf(x, y, z, 0, 0, 0, 1, 0.7, half); };
                        auto c = dt::with_plate_gaps(dt::sample_sdf(solid, -1.1, 1.1, n, seed), holes, kRadius);
                        return std::pair{c, c};
                      }, "1/0/0|1/0/" + std::to_string(2 * holes)});
      }
  return in;
}

std::vector<Input> scan_inputs(const Options& o) {
  std::vector<Input> in;
  const std::string data = o.data + "/data/";
  auto read = [](const std::string& path) {
    auto r = dbss::read_points(path);
    if (!r.ok()) {
      std::fprintf(stderr, "scan_bench: %s\n", r.status().message().c_str());
      return PointCloud{};
    }
    return std::move(r).value();
  };
  for (const char* f : {"hippo1.ply", "half.xyz", "building.ply", "oni.ply", "fin90_with_PCA_normals.xyz", "blobby.xyz"}) {
    const std::string p = data + "points_3/" + f;
    if (!std::filesystem::exists(p)) {
      std::fprintf(stderr, "scan_bench: %s absent (scripts/scan-bench.sh fetches it), skipped\n", p.c_str());
      continue;
    }
    in.push_back({f, [read, p] { auto c = read(p); return std::pair{c, c}; }, ""});
  }
  const std::string bunny = data + "meshes/bunny00.off";
  if (!std::filesystem::exists(bunny)) {
    std::fprintf(stderr, "scan_bench: %s absent (scripts/fetch-test-data.sh), skipped\n", bunny.c_str());
    return in;
  }
  in.push_back({"bunny00.off", [read, bunny] { auto c = read(bunny); return std::pair{c, c}; }, "1/0/0"});
  in.push_back({"bunny +0.5% outliers", [read, bunny] {
                  auto c = read(bunny);
                  return std::pair{dt::with_outliers(c, 0.005, 11), c};
                }, "1/0/0"});
  // The bunny stands on its flat base at the lowest y.
  in.push_back({"bunny bottom 12% cut", [read, bunny] {
                  auto h = dt::with_slab_cut(read(bunny), {0, -1, 0}, 0.12);
                  return std::pair{h, h};
                }, "1/0/0|1/0/1"});
  return in;
}

bool wanted(const Options& o, const std::string& name) {
  if (o.only.empty()) return true;
  for (const std::string& s : o.only)
    if (name.find(s) != std::string::npos) return true;
  return false;
}

int usage(bool error) {
  std::fprintf(error ? stderr : stdout,
               "usage: scan_bench [--levels L] [--points N] [--no-scans] [--data DIR] [--surface auto|closed|open]\n"
               "                  [--keep-outliers] [--hole-sweep | --clean | --plates] [NAME_PART...]\n"
               "--hole-sweep: instead of the table, holes of 10%% and 15%% from six directions in the tori of\n"
               "genus 1-3 (run it with --surface closed to see the closed results alone)\n"
               "--clean: instead of the table, complete scans (tori of genus 1-3 at eight seeds, eight.off and\n"
               "3torus.off sampled, bunny00.off as points) that must keep their topology unwarned\n"
               "--plates: plates with 3-4 round holes through them, and the same plates solid with gaps there\n");
  return error ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--levels" && i + 1 < argc) {
      const int l = std::atoi(argv[++i]);
      if (l < 1 || l > 6) {
        std::fprintf(stderr, "scan_bench: --levels must be 1..6\n");
        return 1;
      }
      o.levels = static_cast<uint32_t>(l);
    } else if (a == "--points" && i + 1 < argc) {
      const long n = std::atol(argv[++i]);
      if (n < 100 || n > 10000000) {
        std::fprintf(stderr, "scan_bench: --points must be 100..10000000\n");
        return 1;
      }
      o.shape_points = static_cast<size_t>(n);
    } else if (a == "--hole-sweep") {
      o.hole_sweep = true;
    } else if (a == "--plates") {
      o.plates = true;
    } else if (a == "--clean") {
      o.clean = true;
    } else if (a == "--no-scans") {
      o.scans = false;
    } else if (a == "--data" && i + 1 < argc) {
      o.data = argv[++i];
#ifdef DBSS_SCAN_CHECK
    } else if (a == "--surface" && i + 1 < argc) {
      const std::string m = argv[++i];
      if (m == "auto") o.surface = dbss::SurfaceMode::automatic;
      else if (m == "closed") o.surface = dbss::SurfaceMode::closed;
      else if (m == "open") o.surface = dbss::SurfaceMode::open;
      else return usage(true);
    } else if (a == "--keep-outliers") {
      o.keep_outliers = true;
#endif
    } else if (a == "--help" || a == "-h") {
      return usage(false);
    } else if (!a.empty() && a[0] == '-') {
      return usage(true);
    } else {
      o.only.push_back(a);
    }
  }

  CompleteScans complete_scans;
  std::vector<Input> inputs = o.hole_sweep ? hole_sweep_inputs(o, complete_scans) : o.clean    ? clean_inputs(o)
                                 : o.plates ? plate_inputs(o)
                                            : defect_inputs(o);
  if (o.scans && !o.hole_sweep && !o.clean && !o.plates)
    for (Input& s : scan_inputs(o)) inputs.push_back(std::move(s));

  std::printf("levels %u, default options; shapes sampled with %zu points\n", o.levels, o.shape_points);
  std::printf("%-28s %7s %4s %5s %5s %4s %7s %9s %7s %7s %4s %6s %7s %-7s %s\n", "input", "points", "comp", "genus",
              "loops", "topo", "clamp%", "p->s/diag", "p->s/sp", "enc s", "exit", "surf", "dropped", "verdict",
              o.hole_sweep ? "warnings  vs-complete joined" : "warnings");
  int failures = 0, silent = 0, wrong_topology = 0, wrong_unwarned = 0, right_warned = 0, joined = 0, over_ratio = 0;
  double worst_ratio = 0;
  // The hole sweep's complete scans, encoded once each: their finest level.
  std::vector<std::pair<std::string, dbss::TriangleMesh>> complete;
  for (const Input& in : inputs) {
    if (!wanted(o, in.name)) continue;
    const auto [points, reference] = in.make();
    std::printf("%-28s %7zu ", in.name.c_str(), points.size());
    std::fflush(stdout);
    dbss::EncodeOptions eo;
    eo.levels = o.levels;
#ifdef DBSS_SCAN_CHECK
    eo.control.surface = o.surface;
    eo.outliers.enabled = !o.keep_outliers;
#endif
    const auto t0 = std::chrono::steady_clock::now();
    const dbss::Status valid = dbss::check_reconstructible(points, in.name);
    dbss::Result<dbss::Encoding> r = valid.ok() ? dbss::encode_points(points, eo) : dbss::Result<dbss::Encoding>(valid);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!r.ok()) {
      ++failures;
      std::printf("%4s %5s %5s %4s %7s %9s %7s %7.2f %4s %6s %7s %-7s %s\n", "-", "-", "-", "-", "-", "-", "-", seconds,
                  "FAIL", "-", "-", "fail", "-");
      std::fflush(stdout);
      std::fprintf(stderr, "scan_bench: %s: %s\n", in.name.c_str(), r.status().to_string().c_str());
      continue;
    }
    const dbss::Encoding& e = r.value();
    const uint32_t L = static_cast<uint32_t>(e.levels.positions.size() - 1);
    const dbss::TriangleMesh finest{e.levels.positions[L], e.levels.triangles[L]};
    const dt::Topology topo = dt::topology(finest);
    const dbss::LevelStats* st = L > 0 ? &e.levels.stats[L - 1] : nullptr;
    const double clamped = st && st->odd ? double(st->clamped) / double(st->odd) : 0.0;
    const double diag = dt::bounds(reference).diagonal();
    const double to_surface = dbss::points_to_mesh(reference.xyz, finest).mean;
    const double spacing = dt::median_spacing(points);
    const bool within = clamped <= 0.02 && to_surface <= 3 * spacing;
    std::string surf = "-", dropped = "-", warnings = "-";
    bool warned = false;
#ifdef DBSS_SCAN_CHECK
    surf = e.stages.open ? "open" : "closed";
    dropped = std::to_string(e.outliers.points_in - e.outliers.kept());
    {
      const dbss::PointIndex index(e.points);
      const dbss::ScanCheck check = dbss::check_scan(e, index);
      warnings.clear();
      for (const dbss::ScanWarning& w : check.warnings) warnings += (warnings.empty() ? "" : ",") + w.code;
      if (warnings.empty()) warnings = "none";
      warned = !check.warnings.empty();
    }
#endif
    const char* verdict = within ? (warned ? "ok+warn" : "ok") : (warned ? "warned" : "SILENT");
    if (!within && !warned) ++silent;
    const std::string got = std::to_string(topo.components) + "/" + std::to_string(topo.genus) + "/" +
                            std::to_string(topo.boundary_loops);
    const char* topo_mark = "?";
    if (!in.expect.empty()) {
      topo_mark = ("|" + in.expect + "|").find("|" + got + "|") != std::string::npos ? "=" : "X";
      if (*topo_mark == 'X') ++wrong_topology, wrong_unwarned += !warned;
      else right_warned += warned;
    }
    std::string sweep;
    const auto source = std::find_if(complete_scans.begin(), complete_scans.end(),
                                     [&](const auto& c) { return in.name.rfind(c.first + " ", 0) == 0; });
    if (source != complete_scans.end()) {
      // The error on the scanned part against the complete scan's: the
      // input's points to this surface over the same points to the
      // complete scan's surface (same options).
      auto it = std::find_if(complete.begin(), complete.end(), [&](const auto& c) { return c.first == source->first; });
      if (it == complete.end()) {
        auto whole = dbss::encode_points(source->second(), eo);
        if (whole.ok()) {
          const dbss::Encoding& w = whole.value();
          complete.emplace_back(source->first, dbss::TriangleMesh{w.levels.positions.back(), w.levels.triangles.back()});
          it = complete.end() - 1;
        }
      }
      char b[64];
      if (it != complete.end()) {
        const double ratio = to_surface / dbss::points_to_mesh(reference.xyz, it->second).mean;
        worst_ratio = std::max(worst_ratio, ratio);
        over_ratio += ratio > 1.3;
        std::snprintf(b, sizeof b, " %6.2f", ratio);
      } else {
        std::snprintf(b, sizeof b, " %6s", "-");
      }
      sweep = b;
#ifdef DBSS_SCAN_CHECK
      sweep += " " + std::to_string(e.tubes.tubes);
      joined += e.tubes.tubes > 0;
#endif
    }
#ifdef DBSS_SCAN_CHECK
    // How bare the least supported handle is (ScanCheck::bare_handle_reach).
    {
      char b[32];
      std::snprintf(b, sizeof b, " bare:%.1f cg:%lld", e.check.bare_handle_reach, static_cast<long long>(e.stages.coarser_genus));
      sweep += b;
    }
#endif
    std::printf("%4u %5lld %5u %4s %7.2f %9.2e %7.2f %7.2f %4s %6s %7s %-7s %-9s%s\n", topo.components,
                static_cast<long long>(topo.genus), topo.boundary_loops, topo_mark, 100 * clamped, to_surface / diag,
                spacing > 0 ? to_surface / spacing : 0.0, seconds, "ok", surf.c_str(), dropped.c_str(), verdict,
                warnings.c_str(), sweep.c_str());
  }
  std::printf("\ncomp, genus, loops: of the level-%u surface (genus summed over components, open ones included);\n"
              "topo: '=' the right ones for the input (a hole: bridged, or open with one loop; a half: cut by z = 0,\n"
              "a disk with genus holes), 'X' not, '?' not known.\n"
              "clamp%%: displacements clamped at level %u.  p->s: the points' mean distance to that surface, measured\n"
              "on the input without the outliers added to it, over its bounding-box diagonal (/diag) and over the\n"
              "input's median spacing (/sp).  verdict: ok = clamp%% <= 2 and p->s <= 3 spacings; warned = outside\n"
              "those bounds with a warning; SILENT = outside them with none.  surf, dropped, warnings: the surface\n"
              "mode chosen, points dropped as outliers and check_scan()'s warning codes ('-': this build has none).\n",
              o.levels, o.levels);
  for (const auto& entry : complete) {
    // The reference surfaces themselves: their topology, and the complete
    // scan's points to them.  (Named, not a structured binding: clang 14
    // refuses a binding captured by a lambda.)
    const std::string& name = entry.first;
    const auto& mesh = entry.second;
    const auto source = std::find_if(complete_scans.begin(), complete_scans.end(), [&](const auto& c) { return c.first == name; });
    const PointCloud whole = source->second();
    const dt::Topology topo = dt::topology(mesh);
    std::printf("complete %-19s %7zu %4u %5lld %5u %20.2e\n", name.c_str(), whole.size(), topo.components,
                static_cast<long long>(topo.genus), topo.boundary_loops,
                dbss::points_to_mesh(whole.xyz, mesh).mean / dt::bounds(whole).diagonal());
  }
  if (o.hole_sweep)
    std::printf("vs-complete: the input's points' mean distance to this surface over theirs to the complete scan's\n"
                "(the error on the scanned part; bound 1.3).  joined: tubes the scan cut through joined across the gap.\n");
  std::printf("%d failed, %d silently outside the bounds, %d with the wrong topology (%d of them without a warning), "
              "%d with the right topology warned\n",
              failures, silent, wrong_topology, wrong_unwarned, right_warned);
  if (o.hole_sweep)
    std::printf("%d with a tube joined, %d over 1.3x the complete scan's error (worst %.2fx)\n", joined, over_ratio,
                worst_ratio);
  return 0;
}
