// Scale on one machine (issue 19 item 3): encode time and peak memory at
// 100k, 1M and 10M points, level 3.  The points are sampled area-uniformly
// with a fixed seed from a mesh the benchmark builds itself (a torus with
// two rings of bumps: genus 1, detail at every level), so nothing is read or
// downloaded.  Each size runs in a child process: its peak resident memory
// (getrusage's ru_maxrss of that child alone) covers sampling and encoding,
// and one size's heap does not inflate the next one's figure.
//
// usage: scale_bench [--levels L] [--threads T] [--keep-outliers] [N...]
//        (default N: 100000 1000000 10000000; --keep-outliers: the encoder's
//        outlier stage off, as for data known to be clean)
//        scale_bench --mesh [--levels L] [--write DIR] [MESH:STEPS[:HOLES]...]
//        mesh input (issue 18): each row is a libcgal-demo mesh (a name under
//        test-data/data/meshes, or a path) Loop-subdivided STEPS times, with
//        HOLES holes cut after that (triangles with a corner within 4% of the
//        diagonal of HOLES vertices spread through the vertex list), encoded
//        by encode_mesh with `dbss encode`'s defaults (auto levels; --levels L:
//        L levels).
//        Default rows: refined_elephant.off:0 (89k triangles),
//        armadillo.off:2 (832k), armadillo.off:2:8 (832k with 8 holes).
//        --write DIR: also writes each row's mesh as DIR/NAME-sSTEPS-hHOLES.ply
//        (to time `dbss encode` on it).  Exits 77 when a mesh is absent.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "dbss/decoder/topology.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/encode_mesh.h"
#include "dbss/io/geometry_files.h"
#include "dbss/measure/loop_subdivision.h"
#include "dbss/measure/surface_samples.h"
#include "cut_holes.h"

namespace {

using Clock = std::chrono::steady_clock;

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// A torus (radii 1 and 0.35) whose tube radius carries 12 x 5 bumps, as a
// 384 x 128 grid of quads split in two: 98k triangles, finer than any
// level-3 surface of the sizes measured.
dbss::TriangleMesh bumpy_torus() {
  constexpr int nu = 384, nv = 128;
  dbss::TriangleMesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
      const double r = 0.35 * (1 + 0.12 * std::sin(12 * u) * std::sin(5 * v));
      m.positions.push_back(static_cast<float>((1 + r * std::cos(v)) * std::cos(u)));
      m.positions.push_back(static_cast<float>((1 + r * std::cos(v)) * std::sin(u)));
      m.positions.push_back(static_cast<float>(r * std::sin(v)));
    }
  const auto id = [&](int i, int j) { return static_cast<uint32_t>((i % nu) * nv + j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

struct Row {
  double sample = 0, encode = 0, encode_cpu = 0, control = 0, levels = 0, outliers = 0;
  double grid = 0, wrap = 0, simplify = 0, check = 0, other = 0;
  int carving_grid = 0;
  size_t shell = 0, control_faces = 0, bytes = 0;
  int ok = 0;
};

// The child: sample, encode, report through the pipe.
[[noreturn]] void child(size_t n, uint32_t levels, unsigned threads, bool outliers, int fd) {
  Row r;
  const auto t0 = Clock::now();
  dbss::PointCloud pc;
  {
    const std::vector<double> p = dbss::sample_surface(bumpy_torus(), n, 19);
    pc.xyz.assign(p.begin(), p.end());
  }
  r.sample = std::chrono::duration<double>(Clock::now() - t0).count();
  dbss::EncodeOptions o;
  o.levels = levels;
  o.threads = threads;
  o.outliers.enabled = outliers;
  const auto t1 = Clock::now();
  const double c1 = cpu_seconds();
  auto e = dbss::encode_points(pc, o);
  r.encode = std::chrono::duration<double>(Clock::now() - t1).count();
  r.encode_cpu = cpu_seconds() - c1;
  if (e.ok()) {
    const dbss::Encoding& x = e.value();
    r.ok = 1;
    r.outliers = x.seconds.outliers;
    r.control = x.seconds.control;
    r.levels = x.seconds.levels;
    r.grid = x.stages.cpu_seconds.grid;
    r.wrap = x.stages.cpu_seconds.shrink_wrap;
    r.simplify = x.stages.cpu_seconds.simplify;
    r.check = x.seconds.check;
    // The input's point index and everything not timed by a stage.
    r.other = r.encode - (x.seconds.outliers + x.seconds.control + x.seconds.draco + x.seconds.levels + x.seconds.check +
                          x.seconds.serialize);
    r.carving_grid = x.stages.carving.grid;
    r.shell = x.stages.shell.triangle_count();
    r.control_faces = x.control.triangle_count();
    r.bytes = x.bytes.size();
  } else {
    std::fprintf(stderr, "scale_bench: %zu points: %s\n", n, e.status().to_string().c_str());
  }
  const ssize_t w = write(fd, &r, sizeof r);
  _exit(w == static_cast<ssize_t>(sizeof r) ? 0 : 1);
}

// --- Mesh input (issue 18) ---

struct MeshRow {
  double encode = 0, encode_cpu = 0, prepare = 0, control = 0, draco = 0, levels = 0, serialize = 0;
  size_t triangles = 0, control_faces = 0, bytes = 0, loops = 0;
  uint32_t level_count = 0;
  int ok = 0;
};

struct MeshSpec {
  std::string path, name;
  int steps = 0;
  uint32_t holes = 0;
};

// Loop subdivision `steps` times: a fixed, finer version of a demo mesh
// (1-to-4 per step), so a 52k-triangle armadillo stands for an 832k scan.
dbss::Result<dbss::TriangleMesh> subdivided(dbss::TriangleMesh m, int steps) {
  for (int s = 0; s < steps; ++s) {
    auto topo = dbss::build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles);
    if (!topo.ok()) return topo.status();
    std::vector<float> next;
    dbss::loop_subdivide(topo.value(), m.positions, next);
    const dbss::LevelTopology child = dbss::refine_topology(topo.value());
    m.positions = std::move(next);
    m.triangles = child.triangles;
  }
  return m;
}

// The child: read, subdivide, cut, encode, report through the pipe.  The
// peak memory covers the generated mesh as well as the encoding.
[[noreturn]] void mesh_child(const MeshSpec& spec, uint32_t levels, unsigned threads, const std::string& write_dir, int fd) {
  MeshRow r;
  auto read = dbss::read_mesh(spec.path);
  auto mesh = read.ok() ? subdivided(std::move(read).value(), spec.steps) : dbss::Result<dbss::TriangleMesh>(read.status());
  if (mesh.ok()) {
    // Holes of 4% of the diagonal, as lod_bench's --cut-holes.
    if (spec.holes) mesh.value() = dbss::bench::cut_holes(mesh.value(), spec.holes, 0.04);
    r.triangles = mesh.value().triangle_count();
    if (!write_dir.empty()) {
      const std::string out = write_dir + "/" + spec.name + "-s" + std::to_string(spec.steps) + "-h" + std::to_string(spec.holes) + ".ply";
      if (dbss::Status st = dbss::write_mesh(out, mesh.value()); !st.ok()) std::fprintf(stderr, "scale_bench: %s\n", st.to_string().c_str());
    }
    dbss::EncodeOptions o;
    o.levels = levels ? levels : dbss::kAutoLevels;  // as `dbss encode`: auto levels by default
    o.threads = threads;
    const auto t1 = Clock::now();
    const double c1 = cpu_seconds();
    auto e = dbss::encode_mesh(mesh.value(), o);
    r.encode = std::chrono::duration<double>(Clock::now() - t1).count();
    r.encode_cpu = cpu_seconds() - c1;
    if (e.ok()) {
      const dbss::Encoding& x = e.value().encoding;
      r.ok = 1;
      r.prepare = x.seconds.outliers;  // encode_mesh: preparing the input and its triangle tree
      r.control = x.seconds.control;
      r.draco = x.seconds.draco;
      r.levels = x.seconds.levels;
      r.serialize = x.seconds.serialize;
      r.level_count = x.level_count;
      r.control_faces = x.control.triangle_count();
      r.bytes = x.bytes.size();
      r.loops = e.value().input_info.boundary_loops;
    } else {
      std::fprintf(stderr, "scale_bench: %s: %s\n", spec.name.c_str(), e.status().to_string().c_str());
    }
  } else {
    std::fprintf(stderr, "scale_bench: %s: %s\n", spec.name.c_str(), mesh.status().to_string().c_str());
  }
  const ssize_t w = write(fd, &r, sizeof r);
  _exit(w == static_cast<ssize_t>(sizeof r) ? 0 : 1);
}

// Runs body(fd) in a child process, which writes one row to fd and exits, so
// that each row's peak memory (use.ru_maxrss) is its own. False when the pipe,
// the fork or the child failed.
template <class Row, class Body>
bool run_in_child(Body body, Row& row, int& status, rusage& use) {
  int fds[2];
  if (pipe(fds) != 0) return std::perror("pipe"), false;
  const pid_t pid = fork();
  if (pid < 0) {
    std::perror("fork");
    close(fds[0]);
    close(fds[1]);
    return false;
  }
  if (pid == 0) {
    close(fds[0]);
    body(fds[1]);
  }
  close(fds[1]);
  const ssize_t got = read(fds[0], &row, sizeof row);
  close(fds[0]);
  status = 0;
  wait4(pid, &status, 0, &use);
  return got == static_cast<ssize_t>(sizeof row) && row.ok;
}

int run_meshes(std::vector<std::string> specs, uint32_t levels, unsigned threads, const std::string& write_dir) {
  if (specs.empty()) specs = {"refined_elephant.off:0", "armadillo.off:2", "armadillo.off:2:8"};
  std::printf("mesh input (encode_mesh), levels %s, %u threads; times in s (encode: wall and CPU of all threads;\n"
              "prep ctrl draco levels ser: wall), memory in MB (peak RSS of the child: reading, subdividing and encoding)\n",
              levels ? std::to_string(levels).c_str() : "auto", threads);
  std::printf("| mesh | steps | holes | triangles | loops | encode | cpu | prep | ctrl | draco | levels | ser | L | ctrlF | bytes | peak MB |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& text : specs) {
    MeshSpec spec;
    const size_t a = text.find(':');
    spec.path = text.substr(0, a);
    if (a != std::string::npos) {
      const size_t b = text.find(':', a + 1);
      spec.steps = std::atoi(text.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1).c_str());
      if (b != std::string::npos) spec.holes = static_cast<uint32_t>(std::atoi(text.substr(b + 1).c_str()));
    }
    if (spec.path.find('/') == std::string::npos) spec.path = "test-data/data/meshes/" + spec.path;
    spec.name = spec.path.substr(spec.path.find_last_of('/') + 1);
    spec.name = spec.name.substr(0, spec.name.find('.'));
    if (access(spec.path.c_str(), R_OK) != 0) {
      std::printf("%s: absent (run from the source tree with test-data linked)\n", spec.path.c_str());
      return 77;
    }
    MeshRow r{};
    int status = 0;
    rusage use{};
    if (!run_in_child([&](int fd) { mesh_child(spec, levels, threads, write_dir, fd); }, r, status, use)) {
      std::printf("| %s | %d | %u | failed (status %d) |\n", spec.name.c_str(), spec.steps, spec.holes, status);
      return 1;
    }
    std::printf("| %s | %d | %u | %zu | %zu | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %u | %zu | %zu | %.0f |\n",
                spec.name.c_str(), spec.steps, spec.holes, r.triangles, r.loops, r.encode, r.encode_cpu, r.prepare, r.control,
                r.draco, r.levels, r.serialize, r.level_count, r.control_faces, r.bytes, static_cast<double>(use.ru_maxrss) / 1024.0);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  uint32_t levels = 0;  // 0: 3 for points, the encoder's default for meshes
  unsigned threads = 2;
  bool outliers = true, meshes = false;
  std::string write_dir;
  std::vector<std::string> mesh_specs;
  std::vector<size_t> sizes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--levels" && i + 1 < argc) levels = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--threads" && i + 1 < argc) threads = static_cast<unsigned>(std::atoi(argv[++i]));
    else if (a == "--keep-outliers") outliers = false;
    else if (a == "--mesh") meshes = true;
    else if (a == "--write" && i + 1 < argc) write_dir = argv[++i];
    else if (!a.empty() && a[0] != '-') {
      mesh_specs.push_back(a);
      sizes.push_back(std::strtoull(a.c_str(), nullptr, 10));
    } else
      return std::fprintf(stderr, "usage: scale_bench [--levels L] [--threads T] [--keep-outliers] [N...]\n"
                                  "       scale_bench --mesh [--levels L] [--threads T] [--write DIR] [MESH:STEPS[:HOLES]...]\n"), 2;
  }
  if (meshes) return run_meshes(mesh_specs, levels, threads, write_dir);
  if (!levels) levels = 3;
  if (sizes.empty()) sizes = {100000, 1000000, 10000000};
  std::printf("bumpy torus sampled with seed 19, level %u, %u threads, outlier stage %s; times in s (encode: wall and CPU of all threads;\n"
              "outlr ctrl levels check other: wall; grid wrap QEM: CPU), memory in MB (peak RSS of the child)\n",
              levels, threads, outliers ? "on" : "off");
  std::printf("%9s | %6s | %7s %7s | %6s %6s %6s %6s %6s %6s %6s %6s | %4s %7s %6s | %8s %7s | %s\n", "points", "sample",
              "encode", "cpu", "outlr", "ctrl", "grid", "wrap", "QEM", "levels", "check", "other", "cgrd", "shellF", "ctrlF",
              "bytes", "peakMB", "x time vs 10x fewer");
  double previous = 0;
  size_t previous_n = 0;
  for (size_t n : sizes) {
    Row r{};
    int status = 0;
    rusage use{};
    if (!run_in_child([&](int fd) { child(n, levels, threads, outliers, fd); }, r, status, use)) {
      std::printf("%9zu | failed (status %d)\n", n, status);
      continue;
    }
    char ratio[32] = "";
    if (previous > 0 && n == 10 * previous_n) std::snprintf(ratio, sizeof ratio, "%.1fx", r.encode / previous);
    std::printf("%9zu | %6.1f | %7.1f %7.1f | %6.1f %6.1f %6.1f %6.1f %6.1f %6.1f %6.1f %6.1f | %4d %7zu %6zu | %8zu %7.0f | %s\n",
                n, r.sample, r.encode, r.encode_cpu, r.outliers, r.control, r.grid, r.wrap, r.simplify, r.levels, r.check, r.other,
                r.carving_grid, r.shell, r.control_faces, r.bytes, static_cast<double>(use.ru_maxrss) / 1024.0, ratio);
    std::fflush(stdout);
    previous = r.encode;
    previous_n = n;
  }
  std::printf("\ntarget (issue 19): 10M points to level 3 in <= 60 s and <= 4096 MB on 2 cores; time <= 12x per 10x points\n");
  return 0;
}
