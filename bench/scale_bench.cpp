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
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "dbss/encoder/encode.h"
#include "dbss/measure/surface_samples.h"

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

}  // namespace

int main(int argc, char** argv) {
  uint32_t levels = 3;
  unsigned threads = 2;
  bool outliers = true;
  std::vector<size_t> sizes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--levels" && i + 1 < argc) levels = static_cast<uint32_t>(std::atoi(argv[++i]));
    else if (a == "--threads" && i + 1 < argc) threads = static_cast<unsigned>(std::atoi(argv[++i]));
    else if (a == "--keep-outliers") outliers = false;
    else if (!a.empty() && a[0] != '-') sizes.push_back(std::strtoull(a.c_str(), nullptr, 10));
    else return std::fprintf(stderr, "usage: scale_bench [--levels L] [--threads T] [--keep-outliers] [N...]\n"), 2;
  }
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
    int fds[2];
    if (pipe(fds) != 0) return std::perror("pipe"), 1;
    const pid_t pid = fork();
    if (pid < 0) return std::perror("fork"), 1;
    if (pid == 0) {
      close(fds[0]);
      child(n, levels, threads, outliers, fds[1]);
    }
    close(fds[1]);
    Row r;
    const ssize_t got = read(fds[0], &r, sizeof r);
    close(fds[0]);
    int status = 0;
    rusage use{};
    wait4(pid, &status, 0, &use);
    if (got != static_cast<ssize_t>(sizeof r) || !r.ok) {
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
