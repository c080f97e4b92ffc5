// LEVL codings side by side on real encodings: for each .dbss file given,
// every level's displacements recoded in each coding (0 byte planes, 1
// varint, both zstd; 2 context, spec section 9b), bits per displacement,
// and the time to decode the file whole (container, Draco, every level) and
// its container alone, with the levels as the zstd codings keep them (the
// smaller of 0 and 1: files before version 1.2) and as the encoder now
// chooses (the smallest of 0, 1, 2), measured in the same run.
//
// usage: entropy_bench FILE.dbss...   (e.g. from `dbss encode X.xyz -o X.dbss`)
#include <cstdio>
#include <string>
#include <vector>

#include "dbss/decoder/progressive.h"
#include "dbss/format/reader.h"
#include "dbss/format/writer.h"
#include "dbss/io/file.h"
#include "timing.h"

using namespace dbss;

namespace {

// The file's contents with every level in `pick(level)`'s coding.
template <class Pick>
std::vector<uint8_t> recode(const format::Reader& r, Pick pick) {
  format::FileContents c;
  c.header = r.header();
  c.control_codec = r.control_codec();
  c.control_mesh.assign(r.control_payload().begin(), r.control_payload().end());
  c.creases = r.creases();
  c.metadata = r.metadata();
  for (uint32_t l = 1; l <= r.levels_ready(); ++l) {
    format::Level level = r.level(l);
    level.coding = pick(level);
    c.levels.push_back(std::move(level));
  }
  c.header.version_minor = format::minimum_version_minor(c);
  return format::serialize(c).value();
}

size_t level_bytes(format::Level level, format::DisplacementCoding coding) {
  level.coding = coding;
  return format::encode_level(level, 19).value().size();
}

format::DisplacementCoding smallest(const format::Level& level, bool with_context) {
  auto best = format::DisplacementCoding::byte_planes;
  size_t bytes = level_bytes(level, best);
  for (auto c : {format::DisplacementCoding::varint, format::DisplacementCoding::context}) {
    if (c == format::DisplacementCoding::context && !with_context) continue;
    const size_t b = level_bytes(level, c);
    if (b < bytes) bytes = b, best = c;
  }
  return best;
}

double decode_seconds(const std::vector<uint8_t>& file, bool container_only) {
  return bench::best_seconds([&] {
    if (container_only) {
      format::Reader r;
      (void)r.feed(file);
      (void)r.finish();
      return;
    }
    DecoderOptions o;
    o.threads = 1;
    ProgressiveDecoder d(o);
    (void)d.feed(file);
    (void)d.finish();
    (void)d.decode_finest();
  }, 1.0);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: entropy_bench FILE.dbss...\n");
    return 1;
  }
  std::printf("| file | level | displacements | non-zero | bits/disp. byte planes | varint | context | chosen before | chosen now |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---|---|\n");
  std::vector<std::string> timing;
  for (int a = 1; a < argc; ++a) {
    auto bytes = io::read_file(argv[a]);
    if (!bytes.ok()) {
      std::fprintf(stderr, "entropy_bench: %s: %s\n", argv[a], bytes.status().to_string().c_str());
      return 1;
    }
    const format::Reader r = format::read_all(bytes.value());
    if (!r.complete()) {
      std::fprintf(stderr, "entropy_bench: %s: %s\n", argv[a], r.status().to_string().c_str());
      return 1;
    }
    std::string name = argv[a];
    name = name.substr(name.find_last_of('/') + 1);
    for (uint32_t l = 1; l <= r.levels_ready(); ++l) {
      const format::Level& level = r.level(l);
      size_t nonzero = 0;
      for (int32_t q : level.q) nonzero += q != 0;
      const double n = static_cast<double>(level.q.size());
      // Chunk data minus its 16 bytes of fields: the payload alone.
      auto bits = [&](format::DisplacementCoding c) { return 8.0 * (level_bytes(level, c) - 16) / n; };
      std::printf("| %s | %u | %zu | %.1f%% | %.3f | %.3f | %.3f | %s | %s |\n", name.c_str(), l, level.q.size(),
                  100.0 * nonzero / n, bits(format::DisplacementCoding::byte_planes),
                  bits(format::DisplacementCoding::varint), bits(format::DisplacementCoding::context),
                  format::coding_name(smallest(level, false)), format::coding_name(smallest(level, true)));
    }
    const auto before = recode(r, [](const format::Level& l) { return smallest(l, false); });
    const auto now = recode(r, [](const format::Level& l) { return smallest(l, true); });
    char line[512];
    std::snprintf(line, sizeof line, "| %s | %zu | %zu | %.3f | %.3f | %.2f | %.2f |", name.c_str(), before.size(),
                  now.size(), 1e3 * decode_seconds(before, true), 1e3 * decode_seconds(now, true),
                  1e3 * decode_seconds(before, false), 1e3 * decode_seconds(now, false));
    timing.push_back(line);
  }
  std::printf("\n| file | bytes before (codings 0/1) | bytes now (0/1/2) | container ms before | now | whole decode ms before | now |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
  for (const std::string& line : timing) std::printf("%s\n", line.c_str());
  return 0;
}
