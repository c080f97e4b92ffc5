#include "dbss/format/status.h"

namespace dbss {

const char* error_code_name(ErrorCode code) noexcept {
  switch (code) {
    case ErrorCode::ok: return "ok";
    case ErrorCode::io: return "io";
    case ErrorCode::bad_signature: return "bad_signature";
    case ErrorCode::unsupported_version: return "unsupported_version";
    case ErrorCode::bad_structure: return "bad_structure";
    case ErrorCode::checksum_mismatch: return "checksum_mismatch";
    case ErrorCode::unknown_critical_chunk: return "unknown_critical_chunk";
    case ErrorCode::bad_field: return "bad_field";
    case ErrorCode::limit_exceeded: return "limit_exceeded";
    case ErrorCode::truncated: return "truncated";
    case ErrorCode::compression: return "compression";
    case ErrorCode::trailing_data: return "trailing_data";
    case ErrorCode::bad_state: return "bad_state";
    case ErrorCode::invalid_argument: return "invalid_argument";
    case ErrorCode::bad_mesh: return "bad_mesh";
    case ErrorCode::internal: return "internal";
  }
  return "unknown_error";
}

std::string Status::to_string() const {
  if (ok()) return "ok";
  std::string s = error_code_name(code_);
  if (offset_ != kNoOffset) s += " at byte " + std::to_string(offset_);
  s += ": ";
  s += message_;
  return s;
}

}  // namespace dbss
