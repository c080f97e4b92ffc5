// decoding.md section 2. Internal to dbss_ref.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "reference.h"

namespace dbss_ref::detail {

// Decodes the Draco payload of CTRL into level 0 and checks it against the
// header's counts. Returns an empty string or the error code name:
// `compression` if Draco refuses the bytes, `bad_mesh` otherwise.
std::string control_mesh(std::span<const uint8_t> payload, uint32_t V0, uint32_t E0, uint32_t F0,
                         Mesh& out);

}  // namespace dbss_ref::detail
