// Rate-distortion of dbss against reconstruct-then-Draco, with errors
// measured against the true surface.  Points are sampled (fixed seed) from
// meshes of Debian's libcgal-demo data, whose surfaces are then the truth:
// dbss encodes the points and every level is decoded from the file prefix
// that holds it; the peers reconstruct a mesh from the same points (CGAL's
// advancing front and Poisson) and compress it with Draco at several
// position quantizations.  Each decoded mesh is compared with the true mesh
// by the two-sided mean distance (dbss/measure/mesh_distance.h) over the true
// mesh's bounding-box diagonal.
//
// usage: rd_bench [--points N] [--noise F] [--levels L] [--qp 8,10,11,12]
//                 [--samples S] [--seed S] [--methods dbss,afront,poisson]
//                 [--csv OUT.csv] [--peers IN.csv] [--control-bits B] [--skip-absent]
//                 [--fixed-control] [--plain-rounding] [--step-bits] [--no-smoothing] [MESH_FILE...]
//   --plain-rounding: the control vertices rounded to Draco's nearest grid
//   point (EncodeOptions::round_along_surface off); --step-bits: Draco's
//   bits from the step (EncodeOptions::control_bits_from_level0 off); both:
//   the control mesh as before issue 15's ninth session.  --no-smoothing:
//   noisy clouds' crossing level as sampled (EncodeOptions::smooth_noise
//   off, as before issue 15's eleventh session).
//   --peers: the peers' rows for each shape are read from the CSV of an
//   earlier run (same --points, --noise, --seed and --samples) instead of
//   reconstructing again (Poisson takes minutes on the armadillo under
//   load); a shape the CSV lacks runs its peers as usual.
//   default meshes: armadillo, fandisk, eight and knot1 from
//   test-data/data/meshes/ (scripts/fetch-test-data.sh).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "dbss/decoder/control_mesh.h"
#include "dbss/decoder/progressive.h"
#include "dbss/encoder/control_mesh_codec.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/point_input.h"
#include "dbss/io/geometry_files.h"
#include "dbss/measure/mesh_distance.h"
#include "dbss/measure/surface_samples.h"
#include "rd_peers.h"
#include "rd_report.h"

namespace {

using dbss::bench::RdRow;
using Clock = std::chrono::steady_clock;

struct Options {
  size_t points = 30000;
  double noise = 0;  // standard deviation per coordinate, over the diagonal
  uint32_t levels = 5;
  std::vector<int> qp = {8, 10, 11, 12};
  size_t samples = 200000;
  uint32_t seed = 1;
  bool dbss = true, afront = true, poisson = true;
  bool fixed_control = false;  // dbss over the default control mesh only (EncodeOptions::choose_control off): the before
  bool skip_absent = false;  // the ctest entry: an absent mesh skips (exit 77) unless CI=true
  int control_bits = 0;      // EncodeOptions::control_bits (0: the encoder's own choice)
  bool plain_rounding = false;  // EncodeOptions::round_along_surface off
  bool step_bits = false;       // EncodeOptions::control_bits_from_level0 off
  bool smoothing = true;        // EncodeOptions::smooth_noise
  std::string csv;
  std::string peers_csv;     // peer rows from an earlier run's CSV
  std::vector<std::string> meshes;
};

constexpr const char* kUsage =
    "usage: rd_bench [--points N] [--noise F] [--levels L] [--qp 8,10,11,12] [--samples S] [--seed S]\n"
    "                [--methods dbss,afront,poisson] [--csv OUT.csv] [--peers IN.csv] [--control-bits B]\n"
    "                [--skip-absent] [--fixed-control] [--plain-rounding] [--step-bits] [--no-smoothing]\n"
    "                [MESH_FILE...]\n";

// "L3", "qp 11".  (Appending, not `"L" + std::to_string(l)`, which GCC 12
// flags with a false -Wrestrict at -O3.)
std::string setting(const char* prefix, long value) {
  std::string s = prefix;
  s += std::to_string(value);
  return s;
}

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

// Parses argv; false after printing a message.
bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--points" && has_value) o.points = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--noise" && has_value) o.noise = std::atof(argv[++i]);
    else if (a == "--levels" && has_value) o.levels = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--samples" && has_value) o.samples = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--seed" && has_value) o.seed = static_cast<uint32_t>(std::strtoul(argv[++i], nullptr, 10));
    else if (a == "--csv" && has_value) o.csv = argv[++i];
    else if (a == "--peers" && has_value) o.peers_csv = argv[++i];
    else if (a == "--control-bits" && has_value) o.control_bits = std::atoi(argv[++i]);
    else if (a == "--plain-rounding") o.plain_rounding = true;
    else if (a == "--step-bits") o.step_bits = true;
    else if (a == "--no-smoothing") o.smoothing = false;
    else if (a == "--skip-absent") o.skip_absent = true;
    else if (a == "--fixed-control") o.fixed_control = true;
    else if (a == "--qp" && has_value) {
      o.qp.clear();
      for (const std::string& q : split(argv[++i])) o.qp.push_back(std::atoi(q.c_str()));
    } else if (a == "--methods" && has_value) {
      o.dbss = o.afront = o.poisson = false;
      for (const std::string& m : split(argv[++i])) {
        if (m == "dbss") o.dbss = true;
        else if (m == "afront") o.afront = true;
        else if (m == "poisson") o.poisson = true;
        else return std::fprintf(stderr, "rd_bench: unknown method %s\n%s", m.c_str(), kUsage), false;
      }
    } else if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (!a.empty() && a[0] == '-') {
      return std::fprintf(stderr, "rd_bench: unknown option %s\n%s", a.c_str(), kUsage), false;
    } else {
      o.meshes.push_back(a);
    }
  }
  if (o.points < 100 || o.levels > 6 || o.samples < 2 || o.noise < 0)
    return std::fprintf(stderr, "rd_bench: need --points >= 100, --levels 0..6, --samples >= 2, --noise >= 0\n"), false;
  for (int q : o.qp)
    if (q < 1 || q > 30) return std::fprintf(stderr, "rd_bench: --qp values must be 1..30\n"), false;
  return true;
}

double diagonal(const dbss::TriangleMesh& m) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < m.positions.size(); ++i) lo[i % 3] = std::min(lo[i % 3], double{m.positions[i]}), hi[i % 3] = std::max(hi[i % 3], double{m.positions[i]});
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

// The benchmark's input: area-uniform points on the truth, with Gaussian
// noise of `noise` diagonals per coordinate (its own stream, so the points'
// positions on the surface do not change with the noise).
dbss::PointCloud sample_points(const dbss::TriangleMesh& truth, const Options& o, double diag) {
  const std::vector<double> p = dbss::sample_surface(truth, o.points, o.seed);
  std::mt19937 rng(o.seed + 1000);
  dbss::PointCloud pc;
  pc.xyz.reserve(p.size());
  for (double x : p) pc.xyz.push_back(static_cast<float>(o.noise > 0 ? x + o.noise * diag * dbss::standard_normal(rng) : x));
  return pc;
}

struct Truth {
  dbss::TriangleMesh mesh;
  double diagonal = 0;
  dbss::MeshDistanceOptions probe;
  double error(const dbss::TriangleMesh& m) const { return dbss::mesh_distance(m, mesh, probe).mean() / diagonal; }
};

// dbss at each level, every level decoded from the prefix of the file that
// holds it, fed to one progressive decoder as a client would receive it.
bool run_dbss(const std::string& shape, const dbss::PointCloud& points, const Truth& truth, const Options& o,
              std::vector<RdRow>& rows) {
  dbss::EncodeOptions eo;
  eo.levels = o.levels;
  eo.choose_control = !o.fixed_control;
  eo.control_bits = o.control_bits;
  eo.round_along_surface = !o.plain_rounding;
  eo.control_bits_from_level0 = !o.step_bits;
  eo.smooth_noise = o.smoothing;
  const auto t0 = Clock::now();
  auto e = dbss::encode_points(points, eo);
  const double seconds = since(t0);
  if (!e.ok()) return std::fprintf(stderr, "rd_bench: %s: dbss: %s\n", shape.c_str(), e.status().to_string().c_str()), false;
  const dbss::Encoding& enc = e.value();
  // Where the encode's time went, and which control mesh it kept.
  std::fprintf(stderr, "rd_bench: %s: dbss %.1f s: control %.1f, draco %.2f, levels %.1f, choice %.1f, check %.1f; control: %s\n",
               shape.c_str(), seconds, enc.seconds.control, enc.seconds.draco, enc.seconds.levels, enc.seconds.choice,
               enc.seconds.check, enc.control_choice.empty() ? "the default (not chosen)" : enc.control_choice.c_str());
  // Where the bytes went: the control mesh (Draco, its position bits) and
  // each level's bits per displacement (LEVL data over its odd vertices).
  std::string per_level;
  for (const dbss::LevelStats& st : enc.levels.stats) {
    char buf[64];
    std::snprintf(buf, sizeof buf, " L%u %.2f", st.level, st.odd ? 8.0 * static_cast<double>(st.bytes) / static_cast<double>(st.odd) : 0.0);
    per_level += buf;
  }
  std::fprintf(stderr,
               "rd_bench: %s: control %zu bytes (%d-bit positions, %zu faces; mean offset along the normal %.3g grid spacings, "
               "%.3g by plain rounding); bits per displacement:%s\n",
               shape.c_str(), enc.contents.control_mesh.size(), enc.control_bits, enc.control.triangle_count(),
               enc.rounding.grid > 0 ? enc.rounding.chosen_normal / enc.rounding.grid : 0.0,
               enc.rounding.grid > 0 ? enc.rounding.nearest_normal / enc.rounding.grid : 0.0, per_level.c_str());
  dbss::ProgressiveDecoder decoder;
  uint64_t fed = 0;
  for (uint32_t l = 0; l <= o.levels; ++l) {
    const uint64_t end = dbss::prefix_bytes(enc, l);
    if (dbss::Status s = decoder.feed({enc.bytes.data() + fed, end - fed}); !s.ok())
      return std::fprintf(stderr, "rd_bench: %s: decoding: %s\n", shape.c_str(), s.to_string().c_str()), false;
    fed = end;
    if (decoder.ready_level() < static_cast<int>(l))
      return std::fprintf(stderr, "rd_bench: %s: level %u not ready after its %llu-byte prefix\n", shape.c_str(), l,
                          static_cast<unsigned long long>(end)), false;
    auto view = decoder.decode(l);
    if (!view.ok()) return std::fprintf(stderr, "rd_bench: %s: level %u: %s\n", shape.c_str(), l, view.status().to_string().c_str()), false;
    const dbss::TriangleMesh m = view.value().copy();
    rows.push_back({shape, "dbss", setting("L", l), end, truth.error(m), m.vertex_count(), m.triangle_count(), seconds});
  }
  return true;
}

// A reconstruction through Draco at each position quantization, decoded back.
bool run_peer(const std::string& shape, const std::string& method, const dbss::bench::Reconstruction& r,
              const Truth& truth, const Options& o, std::vector<RdRow>& rows) {
  if (!r.failure.empty()) {
    std::fprintf(stderr, "rd_bench: %s: %s failed: %s (no rows)\n", shape.c_str(), method.c_str(), r.failure.c_str());
    return true;  // a peer's failure is a result, not a benchmark error
  }
  for (int q : o.qp) {
    const auto t0 = Clock::now();
    // Draco's compression level 7 is encoder speed 3.
    auto bytes = dbss::encode_control_mesh(r.mesh, {q, 3});
    const double seconds = r.seconds + since(t0);
    if (!bytes.ok()) return std::fprintf(stderr, "rd_bench: %s: %s: %s\n", shape.c_str(), method.c_str(), bytes.status().to_string().c_str()), false;
    auto back = dbss::decode_control_mesh(bytes.value(), uint64_t{1} << 32, uint64_t{1} << 32);
    if (!back.ok()) return std::fprintf(stderr, "rd_bench: %s: %s: Draco decode: %s\n", shape.c_str(), method.c_str(), back.status().to_string().c_str()), false;
    const dbss::TriangleMesh& m = back.value();
    rows.push_back({shape, method, setting("qp ", q), bytes.value().size(), truth.error(m), m.vertex_count(),
                    m.triangle_count(), seconds});
  }
  return true;
}

// The peers' rows of `shape` in an earlier run's CSV (write_csv's columns);
// empty when the file or the shape is not there.
std::vector<RdRow> cached_peers(const std::string& path, const std::string& shape) {
  std::vector<RdRow> rows;
  std::FILE* f = std::fopen(path.c_str(), "r");
  if (f == nullptr) return rows;
  char line[512];
  while (std::fgets(line, sizeof line, f) != nullptr) {
    std::string text(line);
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    const std::vector<std::string> c = split(text);
    if (c.size() != 8 || c[0] != shape || c[1] == "dbss" || c[1] == "method") continue;
    rows.push_back({c[0], c[1], c[2], std::strtoull(c[3].c_str(), nullptr, 10), std::atof(c[4].c_str()),
                    std::strtoull(c[5].c_str(), nullptr, 10), std::strtoull(c[6].c_str(), nullptr, 10), std::atof(c[7].c_str())});
  }
  std::fclose(f);
  return rows;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (!parse(argc, argv, o)) return 1;
  if (o.meshes.empty()) {
    const std::string src = DBSS_SOURCE_DIR;
    for (const char* f : {"armadillo.off", "fandisk.off", "eight.off", "knot1.off"}) {
      const std::string p = src + "/test-data/data/meshes/" + f;
      if (std::filesystem::exists(p)) o.meshes.push_back(p);
      else std::fprintf(stderr, "rd_bench: %s absent (scripts/fetch-test-data.sh), skipped\n", p.c_str());
    }
    if (o.meshes.empty()) return std::fprintf(stderr, "rd_bench: no meshes\n"), 1;
  }
  std::printf("rate-distortion: %zu points per shape (seed %u, noise %g of the diagonal), dbss %u levels, Draco qp",
              o.points, o.seed, o.noise, o.levels);
  for (int q : o.qp) std::printf(" %d", q);
  std::printf(" at speed 3;\nerror: two-sided mean distance to the true mesh over its bounding-box diagonal (%zu samples)\n",
              o.samples);
  // Like the tests' scan data (tests/test_data.h): absent data skips a
  // developer's run offline but fails under CI=true.
  const char* ci = std::getenv("CI");
  for (const std::string& path : o.meshes)
    if (o.skip_absent && !std::filesystem::exists(path) && !(ci != nullptr && std::string(ci) == "true"))
      return std::fprintf(stderr, "rd_bench: %s absent (scripts/fetch-test-data.sh): skipped\n", path.c_str()), 77;
  bool csv_header = true;
  for (const std::string& path : o.meshes) {
    auto mesh = dbss::read_mesh(path);
    if (!mesh.ok()) return std::fprintf(stderr, "rd_bench: %s\n", mesh.status().to_string().c_str()), 1;
    const std::string shape = std::filesystem::path(path).stem().string();
    Truth truth{std::move(mesh.value()), 0, {o.samples, o.seed, 2}};
    truth.diagonal = diagonal(truth.mesh);
    const dbss::PointCloud points = sample_points(truth.mesh, o, truth.diagonal);
    if (dbss::Status s = dbss::check_reconstructible(points, shape); !s.ok())
      return std::fprintf(stderr, "rd_bench: %s\n", s.to_string().c_str()), 1;
    std::vector<double> xyz(points.xyz.begin(), points.xyz.end());  // the very same points for the peers

    std::vector<RdRow> rows;
    if (o.dbss && !run_dbss(shape, points, truth, o, rows)) return 1;
    const std::vector<RdRow> cached = o.peers_csv.empty() ? std::vector<RdRow>{} : cached_peers(o.peers_csv, shape);
    if (!cached.empty()) {
      rows.insert(rows.end(), cached.begin(), cached.end());
      std::fprintf(stderr, "rd_bench: %s: %zu peer rows from %s\n", shape.c_str(), cached.size(), o.peers_csv.c_str());
    } else {
      if (o.afront && !run_peer(shape, "advancing front", dbss::bench::advancing_front(xyz), truth, o, rows)) return 1;
      if (o.poisson && !run_peer(shape, "Poisson", dbss::bench::poisson(xyz), truth, o, rows)) return 1;
    }

    char heading[256];
    std::snprintf(heading, sizeof heading, "### %s (%zu triangles, %zu points)", shape.c_str(), truth.mesh.triangle_count(),
                  points.size());
    dbss::bench::print_table(stdout, heading, rows);
    std::fflush(stdout);
    if (!o.csv.empty()) {
      if (!dbss::bench::write_csv(o.csv, rows, csv_header))
        return std::fprintf(stderr, "rd_bench: cannot write %s\n", o.csv.c_str()), 1;
      csv_header = false;
    }
  }
  return 0;
}
