// Checks and payload codings shared by the writer and the reader, so both
// sides enforce one set of rules.  Internal to dbss_format.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "dbss/format/container.h"
#include "dbss/format/status.h"

namespace dbss::format::detail {

// Field ranges of HEAD (spec: "HEAD").  `at` is the offset errors report.
Status check_header(const Header& h, uint64_t at);

// Odd-vertex count of every level 1..h.level_count; fails with bad_field if a
// count overflows.
Status derived_odd_counts(const Header& h, uint64_t at, std::vector<uint64_t>& odd_counts);

// Zigzag + the LEVL coding, before zstd.
std::vector<uint8_t> pack_displacements(std::span<const int32_t> q, DisplacementCoding coding);
// Inverse of pack_displacements; checks raw's size and every value.
Status unpack_displacements(std::span<const uint8_t> raw, DisplacementCoding coding, size_t count,
                            uint64_t at, std::vector<int32_t>& q);

// Valid raw_size for `count` values in `coding`.
bool raw_size_valid(uint64_t raw_size, DisplacementCoding coding, uint64_t count);

// MetaEntry key rule: 1..255 bytes of valid UTF-8 (RFC 3629), no NUL.
bool meta_key_valid(const std::string& key);
bool utf8_valid(std::string_view s);

// The entries of one 'meta' chunk's data (spec section 10); bad_field with
// the offset (`at` + position in `data`) of the first problem.
Status parse_meta(std::span<const uint8_t> data, uint64_t at, std::vector<MetaEntry>& entries);

// CREA chunk data (spec section 10a) for a control mesh of `edges` edges
// and `vertices` vertices.  encode_creases: invalid_argument if the sizes
// differ or no bit is set.  parse_creases: the checks of section 10a in
// order, bad_field with the offset (`at` + position).
Result<std::vector<uint8_t>> encode_creases(const Creases& c, uint32_t edges, uint32_t vertices);
Status parse_creases(std::span<const uint8_t> data, uint32_t edges, uint32_t vertices, uint64_t at, Creases& out);

}  // namespace dbss::format::detail
