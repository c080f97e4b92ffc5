// The codec end to end on the example set: encoder per stage, decoder per
// level, and the comparison against a full-vertex DSS and Draco (the figures
// of `dbss compare`), all measured in one run.
//
// usage: codec_bench [--levels L] [POINT_FILE...]
//   default files: examples/double-torus.xyz, and test-data/data/meshes/
//   bunny00.off, fandisk.off and points_3/kitten.xyz when
//   scripts/fetch-test-data.sh has unpacked them.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <draco/compression/decode.h>

#include "dbss/decoder/progressive.h"
#include "timing.h"
#include "dbss/measure/compare.h"
#include "dbss/encoder/control_mesh_codec.h"
#include "dbss/encoder/point_input.h"

namespace {


using dbss::bench::best_seconds;

struct Result {
  std::string name;
  size_t points = 0;
  dbss::Comparison c;
  std::vector<double> decode_s, draco_decode_s;  // per level
};

}  // namespace

int main(int argc, char** argv) {
  uint32_t levels = 3;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--levels" && i + 1 < argc) {
      levels = static_cast<uint32_t>(std::atoi(argv[++i]));
      if (levels < 1 || levels > 6) {
        std::fprintf(stderr, "codec_bench: --levels must be 1..6\n");
        return 1;
      }
    } else if (a == "--help" || a == "-h" || (!a.empty() && a[0] == '-')) {
      std::fprintf(a == "--help" || a == "-h" ? stdout : stderr, "usage: codec_bench [--levels L] [POINT_FILE...]\n");
      return a == "--help" || a == "-h" ? 0 : 1;
    } else {
      files.push_back(a);
    }
  }
  if (files.empty()) {
    const std::string src = DBSS_SOURCE_DIR;
    files.push_back(src + "/examples/double-torus.xyz");
    for (const char* f : {"data/meshes/bunny00.off", "data/meshes/fandisk.off", "data/points_3/kitten.xyz"}) {
      const std::string p = src + "/test-data/" + f;
      if (std::filesystem::exists(p)) files.push_back(p);
      else std::fprintf(stderr, "codec_bench: %s absent (scripts/fetch-test-data.sh), skipped\n", p.c_str());
    }
  }

  std::vector<Result> results;
  for (const std::string& f : files) {
    auto pts = dbss::read_points(f);
    if (!pts.ok()) {
      std::fprintf(stderr, "codec_bench: %s\n", pts.status().message().c_str());
      return 1;
    }
    dbss::EncodeOptions eo;
    eo.levels = levels;
    eo.threads = 1;
    auto c = dbss::compare_representations(pts.value(), eo);
    if (!c.ok()) {
      std::fprintf(stderr, "codec_bench: %s: %s\n", f.c_str(), c.status().to_string().c_str());
      return 1;
    }
    Result r;
    r.name = std::filesystem::path(f).filename().string();
    r.points = pts.value().size();
    r.c = std::move(c).value();
    const auto& bytes = r.c.encoding.bytes;
    for (uint32_t l = 0; l <= levels; ++l) {
      // A client decoding level L has fetched the file up to L's chunk.
      const size_t prefix = dbss::prefix_bytes(r.c.encoding, l);
      r.decode_s.push_back(best_seconds([&] {
        dbss::DecoderOptions o;
        o.threads = 1;
        dbss::ProgressiveDecoder d(o);
        d.feed({bytes.data(), prefix});
        if (!d.decode(l).ok()) std::abort();
      }));
      const dbss::TriangleMesh mesh{r.c.encoding.levels.positions[l], r.c.encoding.levels.triangles[l]};
      const auto draco_bytes = dbss::encode_control_mesh(mesh, {14, 0}).value();
      r.draco_decode_s.push_back(best_seconds([&] {
        draco::DecoderBuffer buf;
        buf.Init(reinterpret_cast<const char*>(draco_bytes.data()), draco_bytes.size());
        draco::Decoder dec;
        if (!dec.DecodeMeshFromBuffer(&buf).ok()) std::abort();
      }));
    }
    results.push_back(std::move(r));
  }

  std::printf("encoder stages, ms (one thread for the levels)\n");
  std::printf("%-16s %8s %5s %7s %7s %7s %7s %7s %7s %7s %7s %8s %8s\n", "input", "points", "grid", "choose", "carve",
              "triang", "shrink", "QEM", "project", "Draco", "levels", "total", "control");
  for (const Result& r : results) {
    const auto& s = r.c.encoding.stages.seconds;
    const auto& t = r.c.encoding.seconds;
    const double control = s.grid + s.carve + s.triangulate + s.shrink_wrap + s.simplify + s.project;
    std::printf("%-16s %8zu %5d %7.1f %7.1f %7.1f %7.1f %7.1f %7.1f %7.1f %7.1f %8.1f %8.1f\n", r.name.c_str(), r.points,
                r.c.encoding.stages.carving.grid, s.grid * 1e3, s.carve * 1e3, s.triangulate * 1e3, s.shrink_wrap * 1e3,
                s.simplify * 1e3, s.project * 1e3, t.draco * 1e3, t.levels * 1e3,
                (t.control + t.draco + t.levels + t.serialize) * 1e3, control * 1e3);
  }

  std::printf("\nper level: bytes (dbss file prefix; full-vertex DSS, all levels so far; Draco 14-bit on the same mesh),\n"
              "points->surface mean error relative to the diagonal, decode time of that prefix vs Draco's decode\n");
  std::printf("%-16s %2s %8s | %8s %8s %8s %7s %7s | %9s %9s %9s | %8s %8s %6s\n", "input", "L", "tris", "dbss B", "DSS B",
              "Draco14B", "d/DSS", "d/Draco", "dbss err", "DSS err", "Draco err", "dec ms", "Draco ms", "speed");
  for (const Result& r : results)
    for (const dbss::CompareRow& w : r.c.rows) {
      std::printf("%-16s %2u %8zu | %8llu %8llu %8llu %7.3f %7.3f | %9.2e %9.2e %9.2e | %8.3f %8.3f %5.2fx\n",
                  r.name.c_str(), w.level, w.triangles, static_cast<unsigned long long>(w.dbss_bytes),
                  static_cast<unsigned long long>(w.dss_all_bytes), static_cast<unsigned long long>(w.draco_bytes[1]),
                  double(w.dbss_bytes) / double(w.dss_all_bytes), double(w.dbss_bytes) / double(w.draco_bytes[1]),
                  w.dbss_error.to_surface, w.dss_error.to_surface, w.draco_error[1].to_surface,
                  r.decode_s[w.level] * 1e3, r.draco_decode_s[w.level] * 1e3,
                  r.draco_decode_s[w.level] / r.decode_s[w.level]);
    }
  std::printf("\nd/DSS, d/Draco: byte ratios (lower = dbss smaller); speed: Draco decode time / dbss decode time.\n");
  return 0;
}
