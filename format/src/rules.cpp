#include "rules.h"

#include <cmath>
#include <cstring>
#include <string>

#include "byte_io.h"

namespace dbss::format::detail {

Status check_header(const Header& h, uint64_t at) {
  auto bad = [&](const std::string& what) { return Status(ErrorCode::bad_field, "HEAD: " + what, at); };
  if (h.version_major != kVersionMajor)
    return Status(ErrorCode::unsupported_version,
                  "HEAD: format version " + std::to_string(h.version_major) + "." +
                      std::to_string(h.version_minor) + " is not supported (this reader reads 1.x)",
                  at);
  if (h.flags != 0) return bad("flags " + std::to_string(h.flags) + " set; no flag is defined in version 1");
  if (h.level_count > kMaxLevelsInFormat)
    return bad("level_count " + std::to_string(h.level_count) + " over the format's maximum of 30");
  if (h.displacement_mode != 0) return bad("unknown displacement_mode " + std::to_string(h.displacement_mode));
  if (h.control_position_bits > 30)
    return bad("control_position_bits " + std::to_string(h.control_position_bits) + " over 30");
  const uint64_t v = h.control_vertex_count, e = h.control_edge_count, f = h.control_triangle_count;
  if (f < 1 || v < 3) return bad("control mesh needs at least 3 vertices and 1 triangle");
  // Every triangle has 3 edges, each shared by at most two triangles, and
  // every vertex lies on a triangle.
  if (2 * e < 3 * f || e > 3 * f || v > 3 * f)
    return bad("control counts V=" + std::to_string(v) + " E=" + std::to_string(e) + " F=" + std::to_string(f) +
               " cannot belong to a triangle mesh");
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(h.bbox_min[i]) || !std::isfinite(h.bbox_max[i]) || h.bbox_min[i] > h.bbox_max[i])
      return bad("bounding box is not finite or has min > max");
  }
  if (!std::isfinite(h.error_target) || h.error_target < 0) return bad("error_target is negative or not finite");
  return {};
}

Status derived_odd_counts(const Header& h, uint64_t at, std::vector<uint64_t>& odd_counts) {
  const MeshCounts control{h.control_vertex_count, h.control_edge_count, h.control_triangle_count};
  odd_counts.clear();
  for (uint32_t l = 1; l <= h.level_count; ++l) {
    auto n = odd_vertex_count(control, l);
    if (!n) return Status(ErrorCode::bad_field, "HEAD: vertex counts overflow at level " + std::to_string(l), at);
    odd_counts.push_back(*n);
  }
  return {};
}

std::vector<uint8_t> pack_displacements(std::span<const int32_t> q, DisplacementCoding coding) {
  std::vector<uint8_t> raw;
  if (coding == DisplacementCoding::byte_planes) {
    const size_t n = q.size();
    raw.resize(4 * n);
    for (size_t i = 0; i < n; ++i) {
      const uint32_t z = zigzag_encode(q[i]);
      for (size_t k = 0; k < 4; ++k) raw[k * n + i] = static_cast<uint8_t>(z >> (8 * k));
    }
  } else {
    raw.reserve(q.size() * 2);
    for (int32_t v : q) {
      uint32_t z = zigzag_encode(v);
      while (z >= 0x80) {
        raw.push_back(static_cast<uint8_t>(z | 0x80));
        z >>= 7;
      }
      raw.push_back(static_cast<uint8_t>(z));
    }
  }
  return raw;
}

bool raw_size_valid(uint64_t raw_size, DisplacementCoding coding, uint64_t count) {
  if (coding == DisplacementCoding::byte_planes) return raw_size == 4 * count;
  if (coding == DisplacementCoding::context) return raw_size >= 4;  // and = the stream's size (the reader checks)
  return raw_size >= count && raw_size <= 4 * count;
}

Status unpack_displacements(std::span<const uint8_t> raw, DisplacementCoding coding, size_t count, uint64_t at,
                            std::vector<int32_t>& q) {
  constexpr uint32_t kMaxZ = 2u * kMaxAbsDisplacement;  // zigzag of -2^24 - 1 would be 2^25 + 1
  auto bad_value = [&](size_t i) {
    return Status(ErrorCode::bad_field,
                  "LEVL: displacement #" + std::to_string(i) + " is outside -2^24..2^24", at);
  };
  if (!raw_size_valid(raw.size(), coding, count))
    return Status(ErrorCode::bad_field, "LEVL: payload size does not fit the odd-vertex count", at);
  q.resize(count);
  if (coding == DisplacementCoding::byte_planes) {
    const auto z_of = [&](size_t i) {
      return uint32_t{raw[i]} | (uint32_t{raw[count + i]} << 8) | (uint32_t{raw[2 * count + i]} << 16) |
             (uint32_t{raw[3 * count + i]} << 24);
    };
    // One branch-free pass (it vectorises), the range checked once at the
    // end; only a bad payload pays for finding its first bad value.
    uint32_t worst = 0;
    for (size_t i = 0; i < count; ++i) {
      const uint32_t z = z_of(i);
      worst = worst > z ? worst : z;
      q[i] = zigzag_decode(z);
    }
    if (worst > kMaxZ)
      for (size_t i = 0; i < count; ++i)
        if (z_of(i) > kMaxZ) return bad_value(i);
    return {};
  }
  size_t p = 0;
  for (size_t i = 0; i < count; ++i) {
    // Most displacements of fine levels are one byte: eight of them at once
    // when the next eight bytes all lack the continuation bit (such values
    // are canonical and in range, so no check can fail for them).
    while (count - i >= 8 && raw.size() - p >= 8) {
      uint64_t word;
      std::memcpy(&word, raw.data() + p, 8);
      if (word & 0x8080808080808080u) break;
      for (size_t k = 0; k < 8; ++k) q[i + k] = zigzag_decode(raw[p + k]);
      i += 8, p += 8;
    }
    if (i == count) break;
    uint32_t z = 0;
    for (int shift = 0;; shift += 7) {
      if (p >= raw.size())
        return Status(ErrorCode::bad_field, "LEVL: varint payload ends inside value #" + std::to_string(i), at);
      if (shift == 28) return Status(ErrorCode::bad_field, "LEVL: varint #" + std::to_string(i) + " is over 4 bytes", at);
      const uint8_t b = raw[p++];
      z |= uint32_t{b & 0x7Fu} << shift;
      if (!(b & 0x80)) {
        if (b == 0 && shift != 0)
          return Status(ErrorCode::bad_field, "LEVL: varint #" + std::to_string(i) + " is not canonical", at);
        break;
      }
    }
    if (z > kMaxZ) return bad_value(i);
    q[i] = zigzag_decode(z);
  }
  if (p != raw.size()) return Status(ErrorCode::bad_field, "LEVL: varint payload has bytes after the last value", at);
  return {};
}

bool utf8_valid(std::string_view s) {
  // RFC 3629: shortest forms only, no surrogates, nothing past U+10FFFF.
  size_t i = 0;
  const size_t n = s.size();
  while (i < n) {
    const auto b = static_cast<unsigned char>(s[i]);
    size_t more;
    uint32_t cp, min;
    if (b < 0x80) {
      ++i;
      continue;
    } else if ((b & 0xE0) == 0xC0) {
      more = 1, cp = b & 0x1F, min = 0x80;
    } else if ((b & 0xF0) == 0xE0) {
      more = 2, cp = b & 0x0F, min = 0x800;
    } else if ((b & 0xF8) == 0xF0) {
      more = 3, cp = b & 0x07, min = 0x10000;
    } else {
      return false;
    }
    if (n - i - 1 < more) return false;
    for (size_t k = 1; k <= more; ++k) {
      const auto c = static_cast<unsigned char>(s[i + k]);
      if ((c & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (c & 0x3F);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    i += more + 1;
  }
  return true;
}

bool meta_key_valid(const std::string& key) {
  return !key.empty() && key.size() <= 255 && key.find('\0') == std::string::npos && utf8_valid(key);
}

Status parse_meta(std::span<const uint8_t> data, uint64_t at, std::vector<MetaEntry>& entries) {
  const uint8_t* d = data.data();
  const size_t n = data.size();
  auto bad = [&](const std::string& what, size_t p) { return Status(ErrorCode::bad_field, "meta: " + what, at + p); };
  if (n < 4) return bad("chunk too short for its entry count", 0);
  const uint32_t count = load_u32(d);
  if (count > (n - 4) / 6)  // each entry takes at least 1 + 1 + 4 bytes
    return bad(std::to_string(count) + " entries cannot fit in the chunk", 0);
  entries.clear();
  entries.reserve(count);
  size_t p = 4;
  for (uint32_t i = 0; i < count; ++i) {
    const std::string entry = "entry " + std::to_string(i);
    if (n - p < 1) return bad(entry + " cut short", p);
    const size_t klen = d[p++];
    if (n - p < klen + 4) return bad(entry + " cut short", p);
    MetaEntry e;
    e.key.assign(reinterpret_cast<const char*>(d + p), klen);
    if (!meta_key_valid(e.key)) return bad(entry + " has an empty key, a NUL in it or invalid UTF-8", p);
    p += klen;
    const uint32_t vlen = load_u32(d + p);
    p += 4;
    if (n - p < vlen) return bad(entry + " cut short", p);
    e.value.assign(reinterpret_cast<const char*>(d + p), vlen);
    p += vlen;
    entries.push_back(std::move(e));
  }
  if (p != n) return bad("bytes after the last entry", p);
  return {};
}

namespace {
constexpr uint32_t kCreaFixed = 12;  // coding, reserved, the two counts
uint64_t bitmap_bytes(uint32_t n) { return (uint64_t{n} + 7) / 8; }
}  // namespace

Result<std::vector<uint8_t>> encode_creases(const Creases& c, uint32_t edges, uint32_t vertices) {
  if (c.edge.size() != edges || c.corner.size() != vertices)
    return Status(ErrorCode::invalid_argument, "crease tags for " + std::to_string(c.edge.size()) + " edges and " +
                                                   std::to_string(c.corner.size()) + " vertices; the control mesh has " +
                                                   std::to_string(edges) + " and " + std::to_string(vertices));
  std::vector<uint8_t> d(kCreaFixed + bitmap_bytes(edges) + bitmap_bytes(vertices), 0);
  uint32_t crease_count = 0, corner_count = 0;
  uint8_t* bits = d.data() + kCreaFixed;
  for (uint32_t e = 0; e < edges; ++e)
    if (c.edge[e]) bits[e / 8] = static_cast<uint8_t>(bits[e / 8] | 1u << (e % 8)), ++crease_count;
  bits += bitmap_bytes(edges);
  for (uint32_t v = 0; v < vertices; ++v)
    if (c.corner[v]) bits[v / 8] = static_cast<uint8_t>(bits[v / 8] | 1u << (v % 8)), ++corner_count;
  if (crease_count + corner_count == 0)
    return Status(ErrorCode::invalid_argument, "crease tags without a crease or corner: write no CREA chunk");
  for (int k = 0; k < 4; ++k) {
    d[4 + k] = static_cast<uint8_t>(crease_count >> 8 * k);
    d[8 + k] = static_cast<uint8_t>(corner_count >> 8 * k);
  }
  return d;
}

Status parse_creases(std::span<const uint8_t> d, uint32_t edges, uint32_t vertices, uint64_t at, Creases& out) {
  const uint64_t edge_bytes = bitmap_bytes(edges), vertex_bytes = bitmap_bytes(vertices);
  if (d.size() != kCreaFixed + edge_bytes + vertex_bytes)
    return Status(ErrorCode::bad_field,
                  "CREA: " + std::to_string(d.size()) + " bytes, expected " +
                      std::to_string(kCreaFixed + edge_bytes + vertex_bytes) + " for " + std::to_string(edges) +
                      " edges and " + std::to_string(vertices) + " vertices",
                  at);
  if (d[0] != 0) return Status(ErrorCode::bad_field, "CREA: unknown coding " + std::to_string(d[0]), at);
  if (d[1] | d[2] | d[3]) return Status(ErrorCode::bad_field, "CREA: reserved bytes are not zero", at + 1);
  const auto u32 = [&](size_t i) {
    return uint32_t{d[i]} | uint32_t{d[i + 1]} << 8 | uint32_t{d[i + 2]} << 16 | uint32_t{d[i + 3]} << 24;
  };
  const uint32_t crease_count = u32(4), corner_count = u32(8);
  Creases c;
  c.edge.resize(edges);
  c.corner.resize(vertices);
  uint32_t creases = 0, corners = 0;
  const uint8_t* bits = d.data() + kCreaFixed;
  for (uint32_t e = 0; e < edges; ++e) creases += c.edge[e] = static_cast<uint8_t>(bits[e / 8] >> (e % 8) & 1);
  bits += edge_bytes;
  for (uint32_t v = 0; v < vertices; ++v) corners += c.corner[v] = static_cast<uint8_t>(bits[v / 8] >> (v % 8) & 1);
  // Bits past the last edge or vertex in their last byte.
  if (edges % 8 && d[kCreaFixed + edge_bytes - 1] >> (edges % 8))
    return Status(ErrorCode::bad_field, "CREA: padding bits after the last edge are not zero", at + kCreaFixed + edge_bytes - 1);
  if (vertices % 8 && d.back() >> (vertices % 8))
    return Status(ErrorCode::bad_field, "CREA: padding bits after the last vertex are not zero", at + d.size() - 1);
  if (crease_count != creases || corner_count != corners)
    return Status(ErrorCode::bad_field,
                  "CREA: counts say " + std::to_string(crease_count) + " creases and " + std::to_string(corner_count) +
                      " corners, the bits " + std::to_string(creases) + " and " + std::to_string(corners),
                  at + 4);
  if (creases + corners == 0) return Status(ErrorCode::bad_field, "CREA: no crease and no corner", at + 4);
  out = std::move(c);
  return {};
}

}  // namespace dbss::format::detail
