#include <catch2/catch.hpp>

#include <sys/resource.h>

#include <csignal>

#include <filesystem>

#include <cstdint>
#include <vector>

#include "dbss/io/file.h"

using namespace dbss;
using namespace dbss::io;
namespace fs = std::filesystem;

namespace {
fs::path scratch(const char* name) {
  const fs::path d = fs::temp_directory_path() / ("dbss-test-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
// Bytes of a given size with a pattern, so a short or mixed-up write shows.
std::vector<uint8_t> bytes_of(size_t n, uint8_t seed) {
  std::vector<uint8_t> b(n);
  for (size_t i = 0; i < n; ++i) b[i] = static_cast<uint8_t>(seed + i * 131 + (i >> 8));
  return b;
}
size_t entries(const fs::path& d) { return static_cast<size_t>(std::distance(fs::directory_iterator(d), fs::directory_iterator())); }
}  // namespace

TEST_CASE("write_file_atomic writes, replaces, and leaves nothing else behind") {
  const fs::path d = scratch("write");
  const std::string path = (d / "a.dbss").string();
  const auto one = bytes_of(300, 1), two = bytes_of(1 << 20, 7);
  REQUIRE(write_file_atomic(path, one).ok());
  CHECK(read_file(path).value() == one);
  REQUIRE(write_file_atomic(path, two).ok());
  CHECK(read_file(path).value() == two);
  CHECK(entries(d) == 1);
  fs::remove_all(d);
}

TEST_CASE("write_file_atomic failures name the path and keep the old file") {
  const fs::path d = scratch("fail");
  const std::string missing = (d / "no" / "such" / "dir" / "x.dbss").string();
  const Status s = write_file_atomic(missing, bytes_of(300, 1));
  CHECK(s.code() == ErrorCode::io);
  CHECK(s.message().find(missing) != std::string::npos);
  CHECK(entries(d) == 0);
  // A directory in the way is refused and untouched.
  fs::create_directory(d / "dir.dbss");
  const Status t = write_file_atomic((d / "dir.dbss").string(), bytes_of(300, 1));
  CHECK(t.code() == ErrorCode::io);
  CHECK(fs::is_directory(d / "dir.dbss"));
  CHECK(entries(d) == 1);
  fs::remove_all(d);
}

TEST_CASE("a write cut off midway leaves the old file whole and no temporary behind") {
  // The process's file-size limit makes write() fail partway (EFBIG), as a
  // full disk would.
  const fs::path d = scratch("cut");
  const std::string path = (d / "x.dbss").string();
  const std::vector<uint8_t> old(100, 0x42);
  REQUIRE(write_file_atomic(path, old).ok());
  const std::vector<uint8_t> big(64 * 1024, 0x17);
  struct rlimit saved{};
  REQUIRE(getrlimit(RLIMIT_FSIZE, &saved) == 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = saved;
  small.rlim_cur = 4096;
  REQUIRE(setrlimit(RLIMIT_FSIZE, &small) == 0);
  const Status s = write_file_atomic(path, big);
  setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, old_handler);
  CHECK(s.code() == ErrorCode::io);
  CHECK(s.message().find(path) != std::string::npos);
  CHECK(read_file(path).value() == old);
  CHECK(entries(d) == 1);
  fs::remove_all(d);
}

TEST_CASE("read_file names the file and refuses directories and oversize files") {
  const fs::path d = scratch("read");
  CHECK(read_file((d / "absent").string()).status().code() == ErrorCode::io);
  CHECK(read_file((d / "absent").string()).status().message().find("absent") != std::string::npos);
  CHECK(read_file(d.string()).status().code() == ErrorCode::io);
  REQUIRE(write_file_atomic((d / "f").string(), bytes_of(300, 1)).ok());
  CHECK(read_file((d / "f").string(), 10).status().code() == ErrorCode::limit_exceeded);
  fs::remove_all(d);
}
