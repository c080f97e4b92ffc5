// CRC-32C (Castagnoli, reflected polynomial 0x82F63B78), as in iSCSI
// (RFC 3720), ext4 and SCTP.  crc32c("123456789") == 0xE3069283.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace dbss::format {

// Extends `crc` (the value returned for the bytes before) over `bytes`.
// Start with 0; the pre- and post-inversion are handled inside.
uint32_t crc32c_extend(uint32_t crc, std::span<const uint8_t> bytes) noexcept;

inline uint32_t crc32c(std::span<const uint8_t> bytes) noexcept { return crc32c_extend(0, bytes); }

}  // namespace dbss::format
