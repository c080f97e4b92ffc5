// LEVL coding 2 (spec/dbss-format.md section 9b): the displacements of one
// level through an adaptive binary range coder whose probabilities are
// chosen by the magnitudes of the two values before, in odd-vertex order.
// Internal to dbss_format; the writer and the reader share it.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "dbss/format/status.h"

namespace dbss::format::detail {

// The coded stream of `q` (every |q| <= kMaxAbsDisplacement, checked by the
// caller).  Always at least 4 bytes.
std::vector<uint8_t> context_encode(std::span<const int32_t> q);

// Inverse of context_encode for `count` values.  Safe on any bytes: reads
// only `stream`, does a bounded amount of work per value, and fails with
// compression (a byte needed past the end, or bytes left after the last
// value) or bad_field (a magnitude over 2^24).  `at` is the file offset of
// stream[0]; errors carry the offset of the stream byte at fault.
Status context_decode(std::span<const uint8_t> stream, size_t count, uint64_t at, std::vector<int32_t>& q);

}  // namespace dbss::format::detail
