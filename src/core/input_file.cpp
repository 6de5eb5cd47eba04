#include "core/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.hpp"

namespace shpb {
namespace {

std::string kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

std::string read_input_file(const std::filesystem::path& file, const std::string& display,
                            const std::string& expected, std::uintmax_t max_bytes) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0)
    throw input_error(display, "", errno == ENOENT ? "no such file" : std::strerror(errno),
                      "expected an existing " + expected.substr(expected.find(' ') + 1));
  if (!S_ISREG(st.st_mode))
    throw input_error(display, "", kind(st.st_mode), "expected " + expected);
  // O_NONBLOCK: should the path have become a FIFO since stat(), open() still returns at once,
  // and fstat() below refuses it.
  const int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw input_error(display, "", std::strerror(errno), "expected a readable file");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
    throw input_error(display, "", kind(st.st_mode), "expected " + expected);
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes)
    throw input_error(display, "", std::to_string(st.st_size) + " bytes",
                      "expected at most " + std::to_string(max_bytes) + " bytes for " + expected);
  std::string bytes;
  bytes.resize(static_cast<std::size_t>(st.st_size));
  std::size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + got, bytes.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw input_error(display, "", std::strerror(errno), "expected a readable file");
    if (n == 0) break;  // shrank while being read
    got += static_cast<std::size_t>(n);
  }
  bytes.resize(got);
  return bytes;
}

}  // namespace shpb
