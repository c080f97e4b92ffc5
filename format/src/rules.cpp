#include "rules.h"

#include <cmath>
#include <cstring>
#include <string>

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

bool meta_key_valid(const std::string& key) {
  return !key.empty() && key.size() <= 255 && key.find('\0') == std::string::npos;
}

}  // namespace dbss::format::detail
