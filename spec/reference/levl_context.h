// dbss-format.md section 9b: the coded stream of a LEVL chunk of coding 2,
// read as the section describes it, step by step.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace dbss_ref::detail {

// The n displacements coded in `stream` (bytes 16.. of the chunk, at least
// 4), or the section 13 code name of the first error ("compression",
// "bad_field"); empty on success.
const char* decode_context_stream(std::span<const uint8_t> stream, uint64_t n, std::vector<int32_t>& q);

}  // namespace dbss_ref::detail
