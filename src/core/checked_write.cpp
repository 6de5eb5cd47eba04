#include "core/checked_write.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.hpp"

namespace shpb {

void throw_write_error(const std::filesystem::path& file, int error_number) {
  throw WriteError(file.string() + ": cannot be written: " + std::strerror(error_number));
}

void write_text_file(const std::filesystem::path& file, std::string_view text) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw_write_error(file, errno);
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int e = n < 0 ? errno : EIO;
      ::close(fd);
      throw_write_error(file, e);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) throw_write_error(file, errno);
}

void sync_path(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw_write_error(path, errno);
  // EINVAL: a file system without fsync (some pseudo file systems): nothing to make durable.
  if (::fsync(fd) != 0 && errno != EINVAL) {
    const int e = errno;
    ::close(fd);
    throw_write_error(path, e);
  }
  ::close(fd);
}

void sync_tree(const std::filesystem::path& dir) {
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    const auto type = it->symlink_status(ec).type();
    if (type == std::filesystem::file_type::regular ||
        type == std::filesystem::file_type::directory)
      sync_path(it->path());
  }
  if (ec) throw_write_error(dir, ec.value());
  sync_path(dir);
}

}  // namespace shpb
