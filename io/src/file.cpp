// Whole files in and out through POSIX calls: the format and decoder
// libraries work on bytes in memory and never touch the file system.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "dbss/io/file.h"

namespace dbss::io {

namespace {

Status io_error(const std::string& path, const std::string& what, int err) {
  return Status(ErrorCode::io, path + ": " + what + ": " + std::strerror(err));
}

}  // namespace

Status write_file_atomic(const std::string& path, std::span<const uint8_t> bytes) {
  if (path.empty()) return Status(ErrorCode::invalid_argument, "empty output path");
  struct stat st{};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    return Status(ErrorCode::io, path + ": is a directory");
  // Same directory as the target, so the final rename() never crosses file
  // systems and is atomic.
  std::string tmp = path + ".tmp-XXXXXX";
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) return io_error(path, "cannot create a temporary file beside it", errno);
  auto abandon = [&](const std::string& what, int err) {
    ::close(fd);
    ::unlink(tmp.c_str());
    return io_error(path, what, err);
  };
  // mkstemp creates 0600; give the file the permissions a plain open() would.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  if (::fchmod(fd, 0666 & ~mask) != 0) return abandon("cannot set permissions", errno);
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return abandon("write failed", errno);
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0) return abandon("fsync failed", errno);
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    return io_error(path, "close failed", err);
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    return io_error(path, "cannot rename the temporary file into place", err);
  }
  return {};
}

Result<std::vector<uint8_t>> read_file(const std::string& path, uint64_t max_size) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return io_error(path, "cannot open", errno);
  struct stat st{};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    return io_error(path, "cannot stat", err);
  }
  if (S_ISDIR(st.st_mode)) {
    ::close(fd);
    return Status(ErrorCode::io, path + ": is a directory, not a file");
  }
  // Devices and sockets never end (/dev/zero) or block (a terminal); pipes
  // are read up to max_size like files.
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) || S_ISSOCK(st.st_mode)) {
    ::close(fd);
    return Status(ErrorCode::io, path + ": not a regular file (a device or socket)");
  }
  if (S_ISREG(st.st_mode) && static_cast<uint64_t>(st.st_size) > max_size) {
    ::close(fd);
    return Status(ErrorCode::limit_exceeded, path + ": file is over " + std::to_string(max_size) + " bytes");
  }
  std::vector<uint8_t> data;
  uint8_t buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      return io_error(path, "read failed", err);
    }
    if (n == 0) break;
    if (data.size() + static_cast<size_t>(n) > max_size) {
      ::close(fd);
      return Status(ErrorCode::limit_exceeded, path + ": file is over " + std::to_string(max_size) + " bytes");
    }
    data.insert(data.end(), buf, buf + n);
  }
  ::close(fd);
  return data;
}

}  // namespace dbss::io
