// The .dbss version 1 container: the values a file holds, independent of how
// they are read or written.  spec/dbss-format.md is normative; the names here
// follow its tables.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace dbss::format {

// 0x89 'D' 'B' 'S' '\r' '\n' 0x1A '\n': the high bit catches 7-bit channels,
// CR LF and the lone LF catch newline conversion in either direction, 0x1A
// stops `type` on DOS-like systems.
inline constexpr std::array<uint8_t, 8> kSignature = {0x89, 'D', 'B', 'S', '\r', '\n', 0x1A, '\n'};

inline constexpr uint16_t kVersionMajor = 1;
inline constexpr uint16_t kVersionMinor = 0;

// Bytes of the HEAD chunk's data in version 1.0.
inline constexpr uint32_t kHeadSize = 56;
// Length, type and CRC around every chunk's data.
inline constexpr uint32_t kChunkOverhead = 12;
// The format's own ceiling on levels: a file declaring more is invalid.
inline constexpr uint32_t kMaxLevelsInFormat = 30;
// The practical limit on levels: what `dbss encode --levels` and `dbss
// decode --level` accept and what a Reader accepts by default
// (Limits::max_levels).  Each level quadruples the triangles: 8 levels over
// the smallest default control mesh (96 triangles) make 6.3 million, and a
// viewer reaches its memory long before 30.
inline constexpr uint32_t kMaxLevelsInPractice = 8;
// Stored displacement integers satisfy |q| <= kMaxAbsDisplacement so that
// every q converts to binary32 exactly.
inline constexpr int32_t kMaxAbsDisplacement = 1 << 24;

// A chunk type: four ASCII letters.  An upper-case first letter marks a
// critical chunk (a reader that does not know it must reject the file), a
// lower-case one an ancillary chunk (a reader may skip it).
struct ChunkType {
  std::array<char, 4> c{};
  constexpr ChunkType() = default;
  constexpr ChunkType(char a, char b, char d, char e) : c{a, b, d, e} {}
  bool critical() const noexcept { return c[0] >= 'A' && c[0] <= 'Z'; }
  // All four bytes are ASCII letters.
  bool well_formed() const noexcept;
  std::string str() const { return std::string(c.data(), 4); }
  friend bool operator==(const ChunkType&, const ChunkType&) = default;
};

inline constexpr ChunkType kHead{'H', 'E', 'A', 'D'};  // header
inline constexpr ChunkType kIndx{'I', 'N', 'D', 'X'};  // table of contents
inline constexpr ChunkType kCtrl{'C', 'T', 'R', 'L'};  // control mesh
inline constexpr ChunkType kLevl{'L', 'E', 'V', 'L'};  // one subdivision level
inline constexpr ChunkType kMeta{'m', 'e', 't', 'a'};  // key/value metadata
inline constexpr ChunkType kCrea{'C', 'R', 'E', 'A'};  // crease tags (version 1.1)

// The minor version a file with a CREA chunk declares (and needs).
inline constexpr uint16_t kCreaseVersionMinor = 1;
// The minor version a file with a LEVL of coding 2 (context) declares (and
// needs): a 1.1 reader rejects such a LEVL as an unknown coding.
inline constexpr uint16_t kContextCodingVersionMinor = 2;
inline constexpr ChunkType kBdry{'B', 'D', 'R', 'Y'};  // boundary odd vertices' in-surface values (version 1.3)
// The minor version a file with a BDRY chunk declares (and needs): a 1.2
// reader rejects the chunk as an unknown critical type.
inline constexpr uint16_t kBoundaryVersionMinor = 3;

struct Header {
  uint16_t version_major = kVersionMajor;
  uint16_t version_minor = kVersionMinor;
  uint32_t flags = 0;                 // no flag is defined in 1.0: must be 0
  uint8_t level_count = 0;            // LEVL chunks in the file, 0..kMaxLevelsInFormat
  uint8_t displacement_mode = 0;      // 0: one scalar per odd vertex along its unit normal
  uint8_t control_position_bits = 0;  // Draco position quantization bits (informative; 0 = unknown)
  uint32_t control_vertex_count = 0;  // V0 of the control mesh
  uint32_t control_edge_count = 0;    // E0
  uint32_t control_triangle_count = 0;  // F0
  std::array<float, 3> bbox_min{};    // model units; bounds the encoded surface
  std::array<float, 3> bbox_max{};
  float error_target = 0;  // encoder's max quantization error / bbox diagonal (informative; 0 = unset)
  friend bool operator==(const Header&, const Header&) = default;
};

// Vertex, edge and triangle counts of a level.
struct MeshCounts {
  uint64_t vertices = 0, edges = 0, triangles = 0;
  friend bool operator==(const MeshCounts&, const MeshCounts&) = default;
};

// Counts of level `level` (0 = control mesh) from the control mesh's counts,
// by V' = V + E, E' = 2E + 3F, F' = 4F.  nullopt if a count passes 2^62.
std::optional<MeshCounts> counts_at_level(const MeshCounts& control, uint32_t level);

// Number of odd (new) vertices of level `level` >= 1: the edge count of
// level - 1.  nullopt on overflow as above.
std::optional<uint64_t> odd_vertex_count(const MeshCounts& control, uint32_t level);

// Number of boundary edges of level `level` (0 = control mesh): 2E - 3F
// (spec section 9c); nullopt on overflow or if 2E < 3F.
std::optional<uint64_t> boundary_edge_count(const MeshCounts& control, uint32_t level);

struct TocEntry {
  ChunkType type;
  uint32_t length = 0;  // bytes of the chunk's data (without the 12 framing bytes)
  uint64_t offset = 0;  // file offset of the chunk's length field
  uint64_t end() const noexcept { return offset + kChunkOverhead + length; }
  friend bool operator==(const TocEntry&, const TocEntry&) = default;
};

enum class ControlCodec : uint8_t { draco = 0 };

enum class DisplacementCoding : uint8_t {
  byte_planes = 0,  // zigzag u32, all low bytes, then all second bytes, ...
  varint = 1,       // zigzag u32 as canonical LEB128
  context = 2,      // adaptive binary range coder, no zstd (version 1.2, spec section 9b)
};

// "byte_planes", "varint" or "context" (spec section 9's names).
inline const char* coding_name(DisplacementCoding c) {
  return c == DisplacementCoding::byte_planes ? "byte_planes" : c == DisplacementCoding::varint ? "varint" : "context";
}

// A level's BDRY chunk (version 1.3, spec section 9c): one integer per
// boundary edge of the level before, in canonical edge order, moving its
// odd vertex by q * step across the boundary within the surface.  Empty q:
// the level has no BDRY chunk.
struct BoundaryValues {
  DisplacementCoding coding = DisplacementCoding::varint;
  float step = 0;
  std::vector<int32_t> q;
  bool empty() const noexcept { return q.empty(); }
  friend bool operator==(const BoundaryValues&, const BoundaryValues&) = default;
};

struct Level {
  uint8_t index = 0;  // 1..level_count
  DisplacementCoding coding = DisplacementCoding::byte_planes;
  float step = 0;                  // Δ_l in model units, finite and > 0
  std::vector<int32_t> q;          // one per odd vertex, in the spec's odd-vertex order
  BoundaryValues boundary;         // version 1.3; empty without a BDRY chunk
  friend bool operator==(const Level&, const Level&) = default;
};

// Crease tags of the control mesh (spec section 10a), one byte per item,
// 0 or 1: edge[e] for the control mesh's edges in canonical edge order,
// corner[v] per control vertex.  Both empty: no creases (a 1.0 file).
struct Creases {
  std::vector<uint8_t> edge;
  std::vector<uint8_t> corner;
  bool empty() const noexcept { return edge.empty() && corner.empty(); }
  friend bool operator==(const Creases&, const Creases&) = default;
};

struct MetaEntry {
  std::string key;    // 1..255 bytes of UTF-8, no NUL
  std::string value;  // any bytes
  friend bool operator==(const MetaEntry&, const MetaEntry&) = default;
};

// Zigzag maps signed to unsigned so small magnitudes get small codes.
inline uint32_t zigzag_encode(int32_t v) noexcept {
  return (static_cast<uint32_t>(v) << 1) ^ static_cast<uint32_t>(-(static_cast<int64_t>(v) < 0));
}
inline int32_t zigzag_decode(uint32_t z) noexcept {
  return static_cast<int32_t>((z >> 1) ^ (~(z & 1) + 1));
}

}  // namespace dbss::format
