// Container throughput: the push reader against the work it cannot avoid
// (zstd decompression of the level payloads, CRC32C over the file, a plain
// copy of the bytes), all measured in one run on the same synthetic file.
//
// usage: container_bench [levels=4]
#include <zstd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "dbss/format/crc32c.h"
#include "dbss/format/reader.h"
#include "dbss/format/writer.h"

namespace {

using Clock = std::chrono::steady_clock;

template <class F>
double best_seconds(int reps, F&& f) {
  double best = 1e30;
  for (int i = 0; i < reps; ++i) {
    const auto t0 = Clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const int levels = argc > 1 ? std::atoi(argv[1]) : 4;
  if (levels < 1 || levels > 6) {
    std::fprintf(stderr, "usage: container_bench [levels 1..6]\n");
    return 1;
  }
  // A control mesh of a closed genus-0 surface with 10,000 triangles.
  dbss::format::FileContents c;
  c.header.control_triangle_count = 10000;
  c.header.control_edge_count = 15000;
  c.header.control_vertex_count = 5002;
  c.header.level_count = static_cast<uint8_t>(levels);
  c.header.bbox_max = {1, 1, 1};
  c.control_mesh.assign(60000, 0x5A);
  // Displacements shrink level by level, like a converging detail signal.
  std::mt19937 rng(7);
  const dbss::format::MeshCounts control{5002, 15000, 10000};
  size_t total_q = 0;
  for (int l = 1; l <= levels; ++l) {
    dbss::format::Level level;
    level.index = static_cast<uint8_t>(l);
    level.step = 1e-4f;
    std::normal_distribution<double> d(0.0, 200.0 / (1 << l));
    level.q.resize(*dbss::format::odd_vertex_count(control, l));
    for (auto& q : level.q) q = static_cast<int32_t>(std::lround(d(rng)));
    total_q += level.q.size();
    c.levels.push_back(std::move(level));
  }
  std::vector<uint8_t> file;
  const double t_write = best_seconds(1, [&] { file = dbss::format::serialize(c).value(); });

  // Peer: zstd alone on each LEVL frame, as the reader must do.
  const auto probe = dbss::format::read_all(file);
  if (!probe.complete()) {
    std::fprintf(stderr, "bench file did not read back: %s\n", probe.status().to_string().c_str());
    return 2;
  }
  std::vector<std::pair<const uint8_t*, size_t>> frames;
  size_t raw_total = 0;
  for (const auto& e : probe.toc())
    if (e.type == dbss::format::kLevl) {
      const uint8_t* data = file.data() + e.offset + 8;
      frames.push_back({data + 16, e.length - 16});
      uint32_t raw;
      std::memcpy(&raw, data + 12, 4);
      raw_total += raw;
    }
  std::vector<uint8_t> sink(raw_total);

  const int reps = 5;
  const double t_read = best_seconds(reps, [&] {
    auto r = dbss::format::read_all(file);
    if (!r.complete()) std::abort();
  });
  const double t_read_pieces = best_seconds(reps, [&] {
    dbss::format::Reader r;
    for (size_t at = 0; at < file.size(); at += 1460) r.feed({file.data() + at, std::min<size_t>(1460, file.size() - at)});
    if (!r.finish().ok()) std::abort();
  });
  const double t_zstd = best_seconds(reps, [&] {
    size_t at = 0;
    for (auto [p, n] : frames) at += ZSTD_decompress(sink.data() + at, sink.size() - at, p, n);
  });
  volatile uint32_t crc_sink = 0;
  const double t_crc = best_seconds(reps, [&] { crc_sink = dbss::format::crc32c(file); });
  std::vector<uint8_t> copy(file.size());
  const double t_copy = best_seconds(reps, [&] { std::memcpy(copy.data(), file.data(), file.size()); });
  (void)crc_sink;

  const double mb = file.size() / 1e6;
  std::printf("file: %d levels, %zu displacements, %.3f MB (%.3f bits/displacement), written in %.3f s\n\n", levels,
              total_q, mb, 8.0 * (file.size() - 60000) / total_q, t_write);
  std::printf("%-38s %10s %12s %14s\n", "operation", "ms", "MB/s (file)", "Mdispl/s");
  auto row = [&](const char* name, double t) {
    std::printf("%-38s %10.3f %12.1f %14.1f\n", name, t * 1e3, mb / t, total_q / t / 1e6);
  };
  row("dbss reader, whole file", t_read);
  row("dbss reader, 1460-byte pieces", t_read_pieces);
  row("peer: zstd decompress of LEVL frames", t_zstd);
  row("peer: crc32c over the file", t_crc);
  row("floor: memcpy of the file", t_copy);
  std::printf("\nratios: reader / zstd alone = %.2f, reader / (zstd + crc) = %.2f, pieces / whole = %.2f\n",
              t_read / t_zstd, t_read / (t_zstd + t_crc), t_read_pieces / t_read);
  return 0;
}
