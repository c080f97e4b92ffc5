// Decode speed: dbss (whole decode of level L from the file's first bytes up
// to level L's chunk: container, Draco, every level) against
// Draco decoding the identical final mesh, OpenMesh's Modified Butterfly
// subdivider on the same control mesh, and a plain copy of the output arrays
// (the memory floor), into warm memory and into fresh pages (the floor of a
// decoder that returns new arrays), all measured in one run.  dbss also runs
// as one decoder reset() between files, which keeps its memory.
//
// usage: decode_bench [max_level=6]
//        decode_bench --profile L [seconds=5] [threads=1]
//          only dbss's decode of level L, repeated (for perf record); with
//          HOLD=1 in the environment another decoder keeps a decoded level
//          meanwhile (how held memory changes the fresh decodes)
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <draco/compression/decode.h>
#include <sys/mman.h>

#include "../tests/shapes.h"
#include "dbss/decoder/progressive.h"
#include "timing.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/control_mesh_codec.h"
#include "../tests/decoder/file_builder.h"

#ifdef DBSS_HAVE_OPENMESH
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/ModifiedButterFlyT.hh>
#endif

namespace {

using Clock = std::chrono::steady_clock;

using dbss::bench::best_seconds;

// An icosphere with 1280 triangles (valences 5 and 6), jittered.
dbss::TriangleMesh control_mesh() {
  dbss::TriangleMesh m = dbss::test::icosahedron();
  for (int l = 0; l < 3; ++l) {
    auto t = dbss::build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles).value();
    std::vector<float> p = m.positions;
    for (uint32_t e = 0; e < t.edge_count(); ++e) {
      const uint32_t h = t.edge_half[e];
      const uint32_t a = t.triangles[h], b = t.triangles[dbss::next_half(h)];
      for (int k = 0; k < 3; ++k) p.push_back(0.5f * (m.positions[3 * a + k] + m.positions[3 * b + k]));
    }
    dbss::refine_triangles(t, m.triangles);
    m.positions = std::move(p);
  }
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    float* p = &m.positions[3 * v];
    const float r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (int k = 0; k < 3; ++k) p[k] /= r;
  }
  return dbss::test::jitter(m, 0.01f);
}

}  // namespace

// Repeats dbss's decode of `level` for `seconds`, so a profiler sees only it.
int profile(int level, double seconds, unsigned threads) {
  const dbss::TriangleMesh control = control_mesh();
  const auto file = dbss::test::build_file(control, static_cast<uint8_t>(level), 30, 0.002f);
  // CPU time too: on a shared machine it is not inflated by waiting for a core.
  const auto cpu_now = [] {
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
  };
  std::unique_ptr<dbss::ProgressiveDecoder> held;
  if (std::getenv("HOLD")) {
    held = std::make_unique<dbss::ProgressiveDecoder>();
    held->feed(file);
    held->decode(static_cast<uint32_t>(level));
    held->reset();
  }
  int runs = 0;
  double best = 1e30, best_cpu = 1e30;
  const auto start = Clock::now();
  while (std::chrono::duration<double>(Clock::now() - start).count() < seconds) {
    const double c0 = cpu_now();
    const auto t0 = Clock::now();
    dbss::DecoderOptions o;
    o.threads = threads;
    dbss::ProgressiveDecoder d(o);
    d.feed(file);
    if (!d.decode(static_cast<uint32_t>(level)).ok()) std::abort();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
    best_cpu = std::min(best_cpu, cpu_now() - c0);
    ++runs;
  }
  std::printf("level %d, %u thread(s): %d runs, best %.3f ms (cpu time %.3f ms)\n", level, threads, runs, best * 1e3,
              best_cpu * 1e3);
  return 0;
}

int main(int argc, char** argv) {
  if (argc > 2 && std::strcmp(argv[1], "--profile") == 0)
    return profile(std::atoi(argv[2]), argc > 3 ? std::atof(argv[3]) : 5.0,
                   argc > 4 ? static_cast<unsigned>(std::atoi(argv[4])) : 1u);
  const int max_level = argc > 1 ? std::atoi(argv[1]) : 6;
  if (max_level < 3 || max_level > 7) {
    std::fprintf(stderr, "usage: decode_bench [max_level 3..7]\n");
    return 1;
  }
  const dbss::TriangleMesh control = control_mesh();
  const auto file = dbss::test::build_file(control, static_cast<uint8_t>(max_level), 30, 0.002f);
  std::printf("control mesh: %zu vertices, %zu triangles; file with %d levels: %zu bytes\n\n", control.vertex_count(),
              control.triangle_count(), max_level, file.size());
  std::printf("%-5s %10s | %-22s | %-22s | %-22s | %-22s | %-22s | %-22s | %-22s | %s\n", "level", "triangles",
              "dbss 1 thread", "dbss 1 thread, reused", "dbss 2 threads", "Draco (same mesh)", "OpenMesh butterfly", "memcpy of output",
              "copy to fresh pages", "dbss1 vs Draco / OpenMesh / memcpy / fresh | Draco vs fresh");
  std::printf("%-5s %10s |%s\n", "", "", [] {
    static char row[512] = "";
    for (int i = 0; i < 7; ++i) std::snprintf(row + std::strlen(row), sizeof row - std::strlen(row), " %10s %11s |", "ms", "Mtri/s");
    return row;
  }());

  const auto toc = dbss::format::read_all(file).toc();
  std::string draco_other;
  for (int level = 3; level <= max_level; ++level) {
    // A client decoding level L fetches the file up to the end of L's chunk.
    size_t prefix = 0, seen = 0;
    for (const auto& e : toc)
      if (e.type == dbss::format::kLevl && ++seen == static_cast<size_t>(level)) prefix = e.end();
    dbss::TriangleMesh out;
    auto run_dbss = [&](unsigned threads) {
      dbss::DecoderOptions o;
      o.threads = threads;
      dbss::ProgressiveDecoder d(o);
      d.feed({file.data(), prefix});
      auto v = d.decode(static_cast<uint32_t>(level));
      if (!v.ok()) std::abort();
      if (out.positions.empty()) out = v.value().copy();
    };
    const double t1 = best_seconds([&] { run_dbss(1); });
    const double t2 = best_seconds([&] { run_dbss(2); });
    // One decoder over many streams (reset between them) keeps its storage
    // (measured last: the storage it keeps would change the others' memory).
    dbss::DecoderOptions one;
    one.threads = 1;
    dbss::ProgressiveDecoder reused(one);
    const double t1r = best_seconds([&] {
      reused.reset();
      reused.feed({file.data(), prefix});
      if (!reused.decode(static_cast<uint32_t>(level)).ok()) std::abort();
    });
    const double tris = static_cast<double>(out.triangle_count());

    // Draco on the identical final mesh (its defaults: 11-bit positions... we
    // use 16 bits like the control mesh, speed 5).
    auto draco_bytes = dbss::encode_control_mesh(out, {16, 5}).value();
    const double td = best_seconds([&] {
      draco::DecoderBuffer buf;
      buf.Init(reinterpret_cast<const char*>(draco_bytes.data()), draco_bytes.size());
      draco::Decoder dec;
      auto m = dec.DecodeMeshFromBuffer(&buf);
      if (!m.ok()) std::abort();
    });

    double to = 0;
#ifdef DBSS_HAVE_OPENMESH
    using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;
    to = best_seconds([&] {
      OMesh om;
      std::vector<OMesh::VertexHandle> hs;
      for (size_t v = 0; v < control.vertex_count(); ++v)
        hs.push_back(om.add_vertex(OMesh::Point(control.positions[3 * v], control.positions[3 * v + 1], control.positions[3 * v + 2])));
      for (size_t f = 0; f < control.triangle_count(); ++f)
        om.add_face(hs[control.triangles[3 * f]], hs[control.triangles[3 * f + 1]], hs[control.triangles[3 * f + 2]]);
      OpenMesh::Subdivider::Uniform::ModifiedButterflyT<OMesh> sub;
      sub.attach(om);
      sub(static_cast<size_t>(level));
      sub.detach();
    }, 1.0);
#endif
    std::vector<float> pcopy(out.positions.size());
    std::vector<uint32_t> tcopy(out.triangles.size());
    const double tm = best_seconds([&] {
      std::memcpy(pcopy.data(), out.positions.data(), out.positions.size() * 4);
      std::memcpy(tcopy.data(), out.triangles.data(), out.triangles.size() * 4);
    });
    // The same copy into fresh pages (mapped, huge-page advised, written,
    // unmapped): what any decoder that returns new arrays pays at least.
    const double tf = best_seconds([&] {
      const size_t pb = out.positions.size() * 4, tb = out.triangles.size() * 4;
      void* mem = mmap(nullptr, pb + tb, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (mem == MAP_FAILED) std::abort();
      madvise(mem, pb + tb, MADV_HUGEPAGE);
      std::memcpy(mem, out.positions.data(), pb);
      std::memcpy(static_cast<char*>(mem) + pb, out.triangles.data(), tb);
      munmap(mem, pb + tb);
    });
    auto col = [&](double t) { std::printf(" %10.3f %11.1f |", t * 1e3, t > 0 ? tris / t / 1e6 : 0.0); };
    std::printf("%-5d %10.0f |", level, tris);
    col(t1);
    col(t1r);
    col(t2);
    col(td);
    if (to > 0) col(to); else std::printf(" %10s %11s |", "n/a", "n/a");
    col(tm);
    col(tf);
    std::printf(" %.2fx / %.2fx / %.3fx / %.3fx | %.1fx\n", td / t1, to > 0 ? to / t1 : 0.0, tm / t1, tf / t1, td / tf);
    if (level == 5) {
      // The Draco ratio depends on the encoder speed Draco's file was made
      // with (5 is its library default, used above): the other ends.
      for (int speed : {0, 10}) {
        auto bytes = dbss::encode_control_mesh(out, {16, speed}).value();
        const double t = best_seconds([&] {
          draco::DecoderBuffer buf;
          buf.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
          draco::Decoder dec;
          if (!dec.DecodeMeshFromBuffer(&buf).ok()) std::abort();
        });
        draco_other += "  speed " + std::to_string(speed) + ": " + std::to_string(t * 1e3).substr(0, 6) + " ms (" +
                       std::to_string(tris / t / 1e6).substr(0, 4) + " Mtri/s), dbss 1 thread " +
                       std::to_string(t / t1).substr(0, 4) + "x\n";
      }
    }
  }
  if (!draco_other.empty()) std::printf("\nlevel 5, Draco files made at other encoder speeds:\n%s", draco_other.c_str());
  std::printf("\n'reused': one decoder reset between streams, which keeps its storage (no fresh pages).\n"
              "ratios are speed ratios of dbss on one thread (higher = dbss faster; against memcpy and the copy to\n"
              "fresh pages, the share of that memory floor dbss reaches); 'Draco vs fresh' is how many times faster\n"
              "than Draco a decoder returning new arrays could be at most.  One run, best of several repetitions each.\n");
  return 0;
}
