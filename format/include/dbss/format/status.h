// Errors as values for every dbss library boundary.
//
// A Status is either ok or carries an ErrorCode, the byte offset in the
// input where the problem was found (kNoOffset when it is not about a byte
// position) and a human-readable message.  ErrorCode values are pinned: they
// may be stored or compared by callers and never change meaning once released.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <variant>

namespace dbss {

enum class ErrorCode : int {
  ok = 0,
  io = 1,                      // the file system refused (open, read, write, rename)
  bad_signature = 2,           // the first 8 bytes are not a .dbss signature
  unsupported_version = 3,     // a major version this reader does not implement
  bad_structure = 4,           // chunk order, framing or table of contents is wrong
  checksum_mismatch = 5,       // a chunk's CRC32C does not match its bytes
  unknown_critical_chunk = 6,  // a critical chunk type this reader does not know
  bad_field = 7,               // a field holds a value outside its valid range
  limit_exceeded = 8,          // a declared size or count is over a configured limit
  truncated = 9,               // the input ended before the file did
  compression = 10,            // a zstd or Draco payload failed to decode
  trailing_data = 11,          // bytes after the end the table of contents declares
  bad_state = 12,              // API misuse, e.g. feeding a reader that already failed
  invalid_argument = 13,       // a caller passed values a writer cannot store
  bad_mesh = 14,               // mesh connectivity the codec cannot handle
  internal = 15,               // a bug in dbss; please report it
};

// Stable lower-case name of a code, e.g. "checksum_mismatch".
const char* error_code_name(ErrorCode code) noexcept;

class Status {
 public:
  static constexpr uint64_t kNoOffset = ~uint64_t{0};

  Status() = default;  // ok
  Status(ErrorCode code, std::string message, uint64_t offset = kNoOffset)
      : code_(code), offset_(offset), message_(std::move(message)) {}

  bool ok() const noexcept { return code_ == ErrorCode::ok; }
  ErrorCode code() const noexcept { return code_; }
  // Byte offset in the input the error is about, or kNoOffset.
  uint64_t offset() const noexcept { return offset_; }
  const std::string& message() const noexcept { return message_; }
  // "checksum_mismatch at byte 1234: chunk 'LEVL' #2 ..." or "ok".
  std::string to_string() const;

 private:
  ErrorCode code_ = ErrorCode::ok;
  uint64_t offset_ = kNoOffset;
  std::string message_;
};

// Either a value or a non-ok Status.
template <class T>
class Result {
 public:
  Result(T value) : v_(std::move(value)) {}
  Result(Status status) : v_(std::move(status)) {}

  bool ok() const noexcept { return v_.index() == 0; }
  T& value() & { return std::get<0>(v_); }
  const T& value() const& { return std::get<0>(v_); }
  T&& value() && { return std::get<0>(std::move(v_)); }
  // The error; ok Status when the result holds a value.
  Status status() const { return ok() ? Status() : std::get<1>(v_); }

 private:
  std::variant<T, Status> v_;
};

}  // namespace dbss
