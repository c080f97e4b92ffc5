// libFuzzer target: the container reader on arbitrary bytes.
//
// The last input byte picks the piece size the bytes are pushed in (so one
// corpus covers whole and streamed feeding) and whether CRCs are checked.  Oracles (always on, not
// assert()): feeding whole and in pieces agree; a complete file re-serializes
// to bytes that read back to the same contents.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>

#include "dbss/format/reader.h"
#include "dbss/format/writer.h"

namespace {

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "container_fuzzer: oracle failed: %s\n", what);
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace dbss::format;
  if (size == 0) return 0;
  const size_t piece = 1 + (data[size - 1] & 0x7F) % 61;
  const std::span<const uint8_t> bytes(data, size - 1);
  Limits limits;
  limits.max_vertices = 1 << 20;  // keep each run small
  // The mode byte's high bit turns CRC checks off so mutations reach the
  // field checks behind them.
  limits.verify_checksums = !(data[size - 1] & 0x80);

  const Reader whole = read_all(bytes, limits);
  Reader streamed(limits);
  for (size_t at = 0; at < bytes.size() && !streamed.failed(); at += piece)
    streamed.feed(bytes.subspan(at, std::min(piece, bytes.size() - at)));
  streamed.finish();

  check(whole.status().code() == streamed.status().code(), "whole and streamed feeding disagree on the status");
  check(whole.status().offset() == streamed.status().offset(), "whole and streamed feeding disagree on the offset");
  check(whole.levels_ready() == streamed.levels_ready(), "whole and streamed feeding disagree on levels");
  check(whole.levels_ready() <= whole.header().level_count, "more levels than the header declares");
  if (!whole.complete()) return 0;

  FileContents c;
  c.header = whole.header();
  c.control_codec = whole.control_codec();
  c.control_mesh.assign(whole.control_payload().begin(), whole.control_payload().end());
  for (uint32_t l = 1; l <= whole.levels_ready(); ++l) c.levels.push_back(whole.level(l));
  c.metadata = whole.metadata();
  c.creases = whole.creases();
  auto again = serialize(c, {1});
  check(again.ok(), "a file the reader accepted does not serialize");
  limits.verify_checksums = true;  // our own writer's CRCs must hold
  const Reader back = read_all(again.value(), limits);
  check(back.complete(), "re-serialized file does not read back");
  check(back.header() == c.header, "header changed in the round trip");
  for (uint32_t l = 1; l <= back.levels_ready(); ++l) check(back.level(l) == c.levels[l - 1], "level changed");
  check(back.metadata() == c.metadata, "metadata changed in the round trip");
  check(back.creases() == c.creases, "crease tags changed in the round trip");
  return 0;
}
