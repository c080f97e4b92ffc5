// Limits are checked before anything is allocated for a declared size.  The
// global operator new of this test executable records the largest single
// allocation while a probe is armed.
#include <catch2/catch.hpp>

#include <atomic>
#include <cstdlib>
#include <new>

#include "dbss/decoder/progressive.h"
#include "dbss/format/crc32c.h"
#include "samples.h"

namespace {
std::atomic<bool> g_armed{false};
std::atomic<size_t> g_largest{0};
}  // namespace

// Every replaceable form, so allocation and release always pair up (the
// sanitizers check that).
namespace {
void* counted_alloc(size_t n) {
  if (g_armed.load(std::memory_order_relaxed)) {
    size_t seen = g_largest.load();
    while (n > seen && !g_largest.compare_exchange_weak(seen, n)) {}
  }
  return std::malloc(n ? n : 1);
}
}  // namespace

void* operator new(size_t n) {
  if (void* p = counted_alloc(n)) return p;
  throw std::bad_alloc();
}
void* operator new[](size_t n) {
  if (void* p = counted_alloc(n)) return p;
  throw std::bad_alloc();
}
void* operator new(size_t n, const std::nothrow_t&) noexcept { return counted_alloc(n); }
void* operator new[](size_t n, const std::nothrow_t&) noexcept { return counted_alloc(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }
void operator delete[](void* p, size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

using namespace dbss;
using namespace dbss::format;

namespace {
struct Probe {
  Probe() { g_largest = 0, g_armed = true; }
  ~Probe() { g_armed = false; }
  size_t largest() const { return g_largest.load(); }
};

// Re-frames a chunk with a correct CRC after its data was edited in place.
void fix_crc(std::vector<uint8_t>& file, size_t chunk_offset) {
  const uint32_t length = file[chunk_offset] | file[chunk_offset + 1] << 8 | file[chunk_offset + 2] << 16 |
                          uint32_t{file[chunk_offset + 3]} << 24;
  const uint32_t crc = crc32c(std::span<const uint8_t>(file.data() + chunk_offset, 8 + length));
  for (int i = 0; i < 4; ++i) file[chunk_offset + 8 + length + i] = static_cast<uint8_t>(crc >> (8 * i));
}
void put_u32(std::vector<uint8_t>& f, size_t at, uint32_t v) {
  for (int i = 0; i < 4; ++i) f[at + i] = static_cast<uint8_t>(v >> (8 * i));
}
void put_u64(std::vector<uint8_t>& f, size_t at, uint64_t v) {
  for (int i = 0; i < 8; ++i) f[at + i] = static_cast<uint8_t>(v >> (8 * i));
}
constexpr size_t kHeadAt = 8, kHeadData = 16, kIndxAt = 8 + 12 + 56, kIndxData = kIndxAt + 8;
}  // namespace

TEST_CASE("a small file declaring huge counts fails at the header, allocating little") {
  auto file = test::small_file();
  REQUIRE(file.size() < 2048);
  // 2^32 - 1 triangles (with matching edges and vertices) and 30 levels.
  put_u32(file, kHeadData + 12, 0x7FFFFFFF);
  put_u32(file, kHeadData + 16, 0xFFFFFFFF);
  put_u32(file, kHeadData + 20, 0xAAAAAAAA);
  fix_crc(file, kHeadAt);
  {
    Probe probe;
    Reader r;
    const Status s = r.feed(file);
    CHECK(s.code() == ErrorCode::limit_exceeded);
    CHECK(s.offset() <= kHeadData + 56);
    CHECK(probe.largest() < 64 * 1024);
  }
  file[kHeadData + 8] = 30;
  fix_crc(file, kHeadAt);
  {
    Probe probe;
    const Status s = read_all(file).status();
    CHECK((s.code() == ErrorCode::limit_exceeded || s.code() == ErrorCode::bad_field));
    CHECK(s.offset() <= kHeadData + 56);
    CHECK(probe.largest() < 64 * 1024);
  }
}

TEST_CASE("each configurable limit is enforced") {
  const auto file = test::big_file();
  Limits l;
  l.max_levels = 2;
  CHECK(read_all(file, l).status().code() == ErrorCode::limit_exceeded);
  l = {};
  l.max_vertices = 3199;  // level 3 has 3200
  CHECK(read_all(file, l).status().code() == ErrorCode::limit_exceeded);
  l.max_vertices = 3200;
  CHECK(read_all(file, l).complete());
  l = {};
  l.max_file_size = file.size() - 1;
  CHECK(read_all(file, l).status().code() == ErrorCode::limit_exceeded);
  l = {};
  l.max_chunks = 4;  // the file has CTRL, 3 LEVL and meta
  CHECK(read_all(file, l).status().code() == ErrorCode::limit_exceeded);
  l = {};
  l.max_ancillary_bytes = 10;  // the meta chunk is larger
  CHECK(read_all(file, l).status().code() == ErrorCode::limit_exceeded);
}

TEST_CASE("a chunk declaring 3 GiB allocates only for the bytes that arrive") {
  // The last chunk (meta) and its table-of-contents entry both claim 3 GiB;
  // the file is a few hundred bytes.  Nothing is wrong until the input ends.
  auto file = test::small_file();
  const Reader good = read_all(file);
  const size_t n = good.toc().size();
  const size_t entry = kIndxData + 16 + 16 * (n - 1);
  const uint64_t big = 3ull << 30;
  put_u32(file, entry + 4, static_cast<uint32_t>(big));
  put_u64(file, kIndxData, good.toc().back().offset + 12 + big);
  fix_crc(file, kIndxAt);
  put_u32(file, good.toc().back().offset, static_cast<uint32_t>(big));
  Limits l;
  l.max_ancillary_bytes = 0xFFFFFFFFu;
  l.max_file_size = uint64_t{1} << 40;
  Probe probe;
  Reader r(l);
  CHECK(r.feed(file).ok());
  CHECK(r.levels_ready() == 3);
  CHECK(r.finish().code() == ErrorCode::truncated);
  CHECK(probe.largest() < 64 * 1024);
  // With the default ancillary limit the entry alone is refused.
  CHECK(read_all(file).status().code() == ErrorCode::limit_exceeded);
}

TEST_CASE("the progressive decoder refuses a small file declaring 2^40 vertices or 30 levels, allocating little") {
  // A client decoder, default options: the header's declarations are checked
  // against the limits before any mesh memory exists.
  auto file = test::small_file();
  REQUIRE(file.size() < 2048);
  auto refused = [](const std::vector<uint8_t>& f, ErrorCode code = ErrorCode::limit_exceeded) {
    Probe probe;
    ProgressiveDecoder d;
    const Status fed = d.feed(f);
    INFO(fed.to_string());
    CHECK(fed.code() == code);
    CHECK(fed.offset() <= kHeadData + 56);
    CHECK(d.ready_level() == -1);
    CHECK(!d.decode(0).ok());
    CHECK(probe.largest() < 64 * 1024);
  };
  // 12 levels of a small control mesh (the format allows 30; the default
  // limit is 10).
  auto levels12 = file;
  levels12[kHeadData + 8] = 12;
  fix_crc(levels12, kHeadAt);
  refused(levels12);
  // 30 levels of a tetrahedron: level 30 has over 2^62 edges, which breaks
  // the format's own rule; that is checked before the reader's limits (spec
  // section 12), so the code does not depend on them.
  auto levels30 = file;
  levels30[kHeadData + 8] = 30;
  fix_crc(levels30, kHeadAt);
  refused(levels30, ErrorCode::bad_field);
  // A sphere-like control mesh of 2^20 + 2 vertices: level 10 would hold
  // about 2^40 vertices.
  auto huge = file;
  put_u32(huge, kHeadData + 12, (1u << 20) + 2);
  put_u32(huge, kHeadData + 16, 3u << 20);
  put_u32(huge, kHeadData + 20, 2u << 20);
  huge[kHeadData + 8] = 10;
  fix_crc(huge, kHeadAt);
  refused(huge);
  // Even with the level limit raised to the format's 30, the vertex limit
  // holds (20 levels: about 2^45 vertices, under the 2^62 overflow).
  auto levels20 = file;
  levels20[kHeadData + 8] = 20;
  fix_crc(levels20, kHeadAt);
  Limits l;
  l.max_levels = 30;
  Probe probe;
  DecoderOptions o;
  o.limits = l;
  ProgressiveDecoder d(o);
  const Status s = d.feed(levels20);
  INFO(s.to_string());
  CHECK(s.code() == ErrorCode::limit_exceeded);
  CHECK(probe.largest() < 64 * 1024);
}
