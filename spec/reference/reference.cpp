// dbss-format.md: the container, read with the checks of section 12 in
// order, and the loop over levels of decoding.md section 7.
#include "reference.h"

#include <zstd.h>

#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "control_mesh.h"
#include "levl_context.h"

namespace dbss_ref {

namespace {

// Section 12's limits (advice, but the values the reference reader uses).
constexpr uint64_t kMaxFileSize = uint64_t{4} << 30;
constexpr uint32_t kMaxLevels = 10;
constexpr uint64_t kMaxVertices = uint64_t{1} << 26;
constexpr uint32_t kMaxChunks = 4096;
constexpr uint32_t kMaxAncillary = 16u << 20;

// A failed check: the section 13 code name. Thrown inside decode() only.
struct Failure {
  const char* code;
};
[[noreturn]] void fail(const char* code) { throw Failure{code}; }

uint16_t u16(const uint8_t* p) { return uint16_t(p[0] | p[1] << 8); }
uint32_t u32(const uint8_t* p) {
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}
uint64_t u64(const uint8_t* p) { return uint64_t{u32(p)} | uint64_t{u32(p + 4)} << 32; }
float f32(const uint8_t* p) {
  const uint32_t bits = u32(p);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

bool is_letter(uint8_t c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
bool type_is(const uint8_t* p, const char* name) { return std::memcmp(p, name, 4) == 0; }

// Section 6: the header fields that decoding needs.
struct Head {
  uint16_t minor;
  uint8_t level_count;
  uint32_t V0, E0, F0;
  std::vector<uint64_t> edges;  // derived E_l, l = 0..L
  std::vector<uint64_t> faces;  // derived F_l, l = 0..L
};

// Section 7: one table of contents entry.
struct Entry {
  std::array<uint8_t, 4> type;
  uint32_t length;
  uint64_t offset;
};

class Reader {
 public:
  explicit Reader(std::span<const uint8_t> file) : file_(file) {}

  // Section 4: one chunk at file offset `at` whose header must satisfy
  // `header_ok` (else bad_structure); checks the CRC and returns its data.
  template <class HeaderOk>
  std::span<const uint8_t> chunk(uint64_t at, HeaderOk header_ok) {
    need(at, 8);
    const uint32_t length = u32(&file_[at]);
    header_ok(length, &file_[at + 4]);
    need(at, uint64_t{12} + length);
    const std::span<const uint8_t> framed = file_.subspan(at, 8 + size_t{length});
    if (crc32c(framed) != u32(&file_[at + 8 + length])) fail("checksum_mismatch");
    return framed.subspan(8);
  }

  uint64_t size() const { return file_.size(); }

 private:
  // Section 11: running out of bytes inside a chunk is `truncated`.
  void need(uint64_t at, uint64_t count) const {
    if (file_.size() < at || file_.size() - at < count) fail("truncated");
  }
  std::span<const uint8_t> file_;
};

// Section 3.
void check_signature(std::span<const uint8_t> file) {
  static const uint8_t sig[8] = {0x89, 0x44, 0x42, 0x53, 0x0D, 0x0A, 0x1A, 0x0A};
  const size_t n = file.size() < 8 ? file.size() : 8;
  if (n > 0 && std::memcmp(file.data(), sig, n) != 0) fail("bad_signature");  // an empty span may have no data pointer
  if (n < 8) fail("truncated");
}

// Section 6 (after the CRC): fields, derived counts, limits.
Head parse_head(std::span<const uint8_t> d) {
  const uint8_t* p = d.data();
  const uint16_t major = u16(p), minor = u16(p + 2);
  if (minor == 0 && d.size() != 56) fail("bad_structure");  // section 12, HEAD row
  if (major != 1) fail("unsupported_version");
  Head h;
  h.minor = minor;
  h.level_count = p[8];
  h.V0 = u32(p + 12);
  h.E0 = u32(p + 16);
  h.F0 = u32(p + 20);
  if (u32(p + 4) != 0) fail("bad_field");  // flags
  if (h.level_count > 30) fail("bad_field");
  if (p[9] != 0) fail("bad_field");   // displacement_mode
  if (p[10] > 30) fail("bad_field");  // control_position_bits
  if (p[11] != 0) fail("bad_field");  // reserved
  const uint64_t V0 = h.V0, E0 = h.E0, F0 = h.F0;
  if (F0 < 1) fail("bad_field");
  if (V0 < 3 || V0 > 3 * F0) fail("bad_field");
  if (3 * F0 > 2 * E0 || 2 * E0 > 6 * F0) fail("bad_field");
  float lo[3], hi[3];
  for (int c = 0; c < 3; ++c) {
    lo[c] = f32(p + 24 + 4 * c);
    hi[c] = f32(p + 36 + 4 * c);
    if (!std::isfinite(lo[c]) || !std::isfinite(hi[c]) || !(hi[c] >= lo[c])) fail("bad_field");
  }
  const float error_target = f32(p + 48);
  if (!std::isfinite(error_target) || !(error_target >= 0)) fail("bad_field");
  if (u32(p + 52) != 0) fail("bad_field");  // reserved

  // Derived counts of level L, each at most 2^62. With every count of level
  // l at most 2^62, 2E + 3F can reach 5 * 2^62, so work in 128 bits.
  __extension__ typedef unsigned __int128 u128;
  const u128 cap = u128{1} << 62;
  u128 V = V0, E = E0, F = F0;
  h.edges.push_back(E0);
  h.faces.push_back(F0);
  for (uint32_t l = 0; l < h.level_count; ++l) {
    const u128 V1 = V + E, E1 = 2 * E + 3 * F, F1 = 4 * F;
    V = V1, E = E1, F = F1;
    if (V > cap || E > cap || F > cap) fail("bad_field");
    h.edges.push_back(static_cast<uint64_t>(E));
    h.faces.push_back(static_cast<uint64_t>(F));
  }
  // Section 12's limits apply here, before anything else is read.
  if (h.level_count > kMaxLevels) fail("limit_exceeded");
  if (V > kMaxVertices) fail("limit_exceeded");
  return h;
}

// Section 7 (after the CRC): the entries and rules 1-6.
std::vector<Entry> parse_index(std::span<const uint8_t> d, uint64_t body_start, const Head& head) {
  const uint8_t* p = d.data();
  const uint64_t file_size = u64(p);
  const uint32_t n = u32(p + 8);
  if (n < 1 || n != (d.size() - 16) / 16) fail("bad_structure");
  if (u32(p + 12) != 0) fail("bad_field");  // reserved
  std::vector<Entry> entries(n);
  uint64_t expected = body_start;
  uint32_t ctrl = 0, levl = 0, crea = 0;
  bool bdry_seen = false, bdry_pending = false;
  for (uint32_t i = 0; i < n; ++i) {
    const uint8_t* e = p + 16 + 16 * size_t{i};
    Entry& entry = entries[i];
    std::memcpy(entry.type.data(), e, 4);
    entry.length = u32(e + 4);
    entry.offset = u64(e + 8);
    for (uint8_t c : entry.type)
      if (!is_letter(c)) fail("bad_structure");
    if (entry.offset != expected) fail("bad_structure");  // rule 1
    expected += 12 + uint64_t{entry.length};
    if (type_is(e, "HEAD") || type_is(e, "INDX")) fail("bad_structure");  // rule 3
    if (type_is(e, "CTRL")) {
      if (++ctrl > 1 || levl > 0) fail("bad_structure");  // rule 4
    } else if (type_is(e, "LEVL")) {
      ++levl;
      bdry_pending = false;
    } else if (type_is(e, "CREA") && head.minor >= 1) {
      if (++crea > 1 || ctrl == 0 || levl > 0 || bdry_seen) fail("bad_structure");  // rule 8
    } else if (type_is(e, "BDRY") && head.minor >= 3) {
      if (ctrl == 0 || bdry_pending) fail("bad_structure");  // rule 9
      bdry_seen = bdry_pending = true;
    } else if (e[0] >= 'A' && e[0] <= 'Z') {
      fail("unknown_critical_chunk");  // rule 6
    }
  }
  if (file_size != expected) fail("bad_structure");    // rule 2
  if (ctrl != 1) fail("bad_structure");                // rule 4
  if (levl != head.level_count) fail("bad_structure");  // rule 5
  if (bdry_pending) fail("bad_structure");              // rule 9: a LEVL after the last BDRY
  if (file_size > kMaxFileSize) fail("limit_exceeded");
  for (const Entry& entry : entries)
    if (entry.type[0] >= 'a' && entry.length > kMaxAncillary) fail("limit_exceeded");
  return entries;
}

// Rule 2: file_size is the end of the last entry.
uint64_t end_of_last_entry(const std::vector<Entry>& entries) {
  return entries.back().offset + 12 + entries.back().length;
}

// Section 8 and decoding.md section 2.
Mesh read_ctrl(std::span<const uint8_t> d, const Head& head) {
  if (d.size() <= 4) fail("bad_field");  // payload at least 1 byte
  if (d[0] != 0) fail("bad_field");      // codec 0: Draco
  if (d[1] != 0 || d[2] != 0 || d[3] != 0) fail("bad_field");
  Mesh level0;
  const std::string error = detail::control_mesh(d.subspan(4), head.V0, head.E0, head.F0, level0);
  if (!error.empty()) throw Failure{error == "compression" ? "compression" : "bad_mesh"};
  return level0;
}

// Section 9: the displacements q of LEVL number `level`, which refines a
// mesh of `edges` edges.
struct Levl {
  std::vector<int32_t> q;
  float step = 0;
};

// Section 9c: a BDRY chunk has the same fields, with boundary_count =
// B_{level-1} (which must be at least 1) for odd_count.
Levl read_levl(std::span<const uint8_t> d, uint32_t level, uint64_t edges, uint16_t minor) {
  if (d.size() < 16) fail("bad_field");  // too short for its fields (section 9, check 1)
  const uint8_t* p = d.data();
  if (p[0] != level) fail("bad_structure");  // out of order (check 2)
  const uint8_t coding = p[1];
  if (coding > (minor >= 2 ? 2 : 1)) fail("bad_field");  // coding 2: version 1.2
  if (u16(p + 2) != 0) fail("bad_field");
  const uint32_t odd_count = u32(p + 4);
  if (odd_count != edges || edges == 0) fail("bad_field");
  Levl out;
  out.step = f32(p + 8);
  if (!std::isfinite(out.step) || !(out.step > 0)) fail("bad_field");
  const uint32_t raw_size = u32(p + 12);
  const uint64_t n = odd_count;
  if (coding == 0 && raw_size != 4 * n) fail("bad_field");
  if (coding == 1 && (raw_size < n || raw_size > 4 * n)) fail("bad_field");
  if (coding == 2) {
    // Section 9b: no zstd; the stream is the rest of the chunk.
    if (raw_size != d.size() - 16 || raw_size < 4) fail("bad_field");
    const char* error = detail::decode_context_stream(d.subspan(16), n, out.q);
    if (*error) fail(error);
    return out;
  }

  // Exactly one zstd frame, decompressing to exactly raw_size bytes.
  const std::span<const uint8_t> frame = d.subspan(16);
  const size_t frame_size = ZSTD_findFrameCompressedSize(frame.data(), frame.size());
  if (ZSTD_isError(frame_size) || frame_size != frame.size()) fail("compression");
  const unsigned long long declared = ZSTD_getFrameContentSize(frame.data(), frame.size());
  if (declared == ZSTD_CONTENTSIZE_ERROR) fail("compression");
  if (declared != ZSTD_CONTENTSIZE_UNKNOWN && declared != raw_size) fail("compression");
  std::vector<uint8_t> raw(raw_size);
  const size_t got = ZSTD_decompress(raw.data(), raw.size(), frame.data(), frame.size());
  if (ZSTD_isError(got) || got != raw_size) fail("compression");

  // Zigzag values z, then q; |q| <= 2^24 means z <= 2^25.
  out.q.resize(n);
  size_t at = 0;
  for (uint64_t i = 0; i < n; ++i) {
    uint32_t z = 0;
    if (coding == 0) {
      for (int k = 0; k < 4; ++k) z |= uint32_t{raw[k * n + i]} << (8 * k);
    } else {
      // Unsigned LEB128, at most 4 bytes, shortest form.
      for (int k = 0;; ++k) {
        if (k == 4 || at == raw.size()) fail("bad_field");
        const uint8_t b = raw[at++];
        z |= uint32_t{b & 0x7Fu} << (7 * k);
        if ((b & 0x80) == 0) {
          if (b == 0 && k > 0) fail("bad_field");  // not the shortest encoding
          break;
        }
      }
    }
    if (z > (1u << 25)) fail("bad_field");
    out.q[i] = int32_t(z >> 1) ^ -int32_t(z & 1);
  }
  if (coding == 1 && at != raw.size()) fail("bad_field");  // left-over bytes
  return out;
}

// Section 10a: the crease tags, one byte per edge and per vertex.
void read_crea(std::span<const uint8_t> d, const Head& head, Mesh& level0) {
  const uint64_t edge_bytes = (uint64_t{head.E0} + 7) / 8, vertex_bytes = (uint64_t{head.V0} + 7) / 8;
  if (d.size() != 12 + edge_bytes + vertex_bytes) fail("bad_field");  // check 1
  if (d[0] != 0) fail("bad_field");                                   // 2: coding
  if (d[1] != 0 || d[2] != 0 || d[3] != 0) fail("bad_field");         // 3: reserved
  const auto bit = [&](uint64_t byte, uint32_t i) { return (d[12 + byte + i / 8] >> (i % 8)) & 1; };
  for (uint32_t i = head.E0; i < 8 * edge_bytes; ++i)  // 4: padding, edge map then vertex map
    if (bit(0, i)) fail("bad_field");
  for (uint32_t i = head.V0; i < 8 * vertex_bytes; ++i)
    if (bit(edge_bytes, i)) fail("bad_field");
  level0.crease.assign(head.E0, 0);
  level0.corner.assign(head.V0, 0);
  uint32_t creases = 0, corners = 0;
  for (uint32_t e = 0; e < head.E0; ++e) creases += level0.crease[e] = static_cast<uint8_t>(bit(0, e));
  for (uint32_t v = 0; v < head.V0; ++v) corners += level0.corner[v] = static_cast<uint8_t>(bit(edge_bytes, v));
  if (u32(d.data() + 4) != creases || u32(d.data() + 8) != corners) fail("bad_field");  // 5
  if (creases + corners == 0) fail("bad_field");                                          // 6
}

// Section 10.
void check_meta(std::span<const uint8_t> d) {
  if (d.size() < 4) fail("bad_field");
  const uint32_t count = u32(d.data());
  size_t at = 4;
  for (uint32_t i = 0; i < count; ++i) {
    if (d.size() - at < 1) fail("bad_field");
    const uint8_t key_length = d[at++];
    if (key_length == 0 || d.size() - at < key_length) fail("bad_field");
    for (size_t k = 0; k < key_length; ++k)
      if (d[at + k] == 0) fail("bad_field");
    at += key_length;
    if (d.size() - at < 4) fail("bad_field");
    const uint32_t value_length = u32(&d[at]);
    at += 4;
    if (d.size() - at < value_length) fail("bad_field");
    at += value_length;
  }
  if (at != d.size()) fail("bad_field");
}

}  // namespace

uint32_t crc32c(std::span<const uint8_t> bytes) {
  // Section 5's bitwise definition, one table entry per byte value.
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t b = 0; b < 256; ++b) {
      uint32_t c = b;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ ((c & 1) ? 0x82F63B78u : 0u);
      t[b] = c;
    }
    return t;
  }();
  uint32_t c = 0xFFFFFFFFu;
  for (uint8_t b : bytes) c = (c >> 8) ^ table[(c ^ b) & 0xFF];
  return c ^ 0xFFFFFFFFu;
}

Decoded decode(std::span<const uint8_t> file) {
  Decoded out;
  try {
    Reader reader(file);
    check_signature(file);

    // HEAD at file offset 8: type HEAD, length 56..1024.
    const auto head_data = reader.chunk(8, [](uint32_t length, const uint8_t* type) {
      if (!type_is(type, "HEAD") || length < 56 || length > 1024) fail("bad_structure");
    });
    const Head head = parse_head(head_data);

    // INDX right after: length 16 + 16 N, N >= 1; the chunk limit applies
    // to N before its bytes are read.
    const uint64_t indx_at = 8 + 12 + uint64_t{head_data.size()};
    const auto indx_data = reader.chunk(indx_at, [](uint32_t length, const uint8_t* type) {
      if (!type_is(type, "INDX") || length < 32 || (length - 16) % 16 != 0) fail("bad_structure");
      if ((length - 16) / 16 > kMaxChunks) fail("limit_exceeded");
    });
    const uint64_t body_at = indx_at + 12 + indx_data.size();
    const std::vector<Entry> entries = parse_index(indx_data, body_at, head);

    // Body chunks in file order.
    uint32_t level = 0;
    Levl bdry;  // section 9c: the BDRY chunk of the next LEVL, if any
    bool have_bdry = false;
    for (const Entry& entry : entries) {
      const auto data = reader.chunk(entry.offset, [&](uint32_t length, const uint8_t* type) {
        if (std::memcmp(type, entry.type.data(), 4) != 0 || length != entry.length)
          fail("bad_structure");  // rule 7
      });
      if (type_is(entry.type.data(), "CTRL")) {
        out.levels.push_back(read_ctrl(data, head));
      } else if (type_is(entry.type.data(), "CREA")) {
        read_crea(data, head, out.levels.back());  // placed after CTRL by rule 8
      } else if (type_is(entry.type.data(), "LEVL")) {
        ++level;
        // decoding.md section 2 step 6, checked when level 1 is computed.
        if (level == 1 && !detail::creases_fit(out.levels.back())) fail("bad_mesh");
        // odd_count = E_{level-1}, from the derived counts.
        const Levl levl = read_levl(data, level, head.edges[level - 1], head.minor);
        // Level l+1 from the displaced level l (decoding.md sections 7 and 7a).
        out.levels.push_back(subdivide(out.levels.back(), levl.q, levl.step, nullptr,
                                       have_bdry ? std::span<const int32_t>(bdry.q) : std::span<const int32_t>(),
                                       bdry.step));
        have_bdry = false;
      } else if (type_is(entry.type.data(), "BDRY")) {
        // Section 9c: B_{l} = 2 E_l - 3 F_l for the level l it refines.
        const uint64_t boundary = 2 * head.edges[level] - 3 * head.faces[level];
        bdry = read_levl(data, level + 1, boundary, 2);  // codings 0..2 in any 1.3 file
        have_bdry = true;
      } else if (type_is(entry.type.data(), "meta")) {
        check_meta(data);
      }
      // Other ancillary chunks: skipped, their CRC verified by chunk().
    }
    // Rule 2: nothing follows the last entry.
    if (reader.size() > end_of_last_entry(entries)) fail("trailing_data");
  } catch (const Failure& failure) {
    out.error = failure.code;
  }
  return out;
}

}  // namespace dbss_ref
