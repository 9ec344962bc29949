#include "support/InputFile.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace cbtl::support {

namespace {

// Closes the descriptor on every path out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string describeBytes(std::uintmax_t bytes) {
  if (bytes >= kMiB && bytes % kMiB == 0) return fmt::format("{} MiB", bytes / kMiB);
  if (bytes >= 1024 && bytes % 1024 == 0) return fmt::format("{} KiB", bytes / 1024);
  return fmt::format("{} bytes", bytes);
}

std::string readInputFile(const std::string& path, std::uintmax_t maxBytes, std::string_view what) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer before fstat could refuse it.
  Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (file.fd < 0)
    throw InputFileError(InputFileError::Kind::CannotOpen, path,
                         fmt::format("cannot read the {} ({})", what, std::strerror(errno)));
  struct stat info {};
  if (::fstat(file.fd, &info) != 0)
    throw InputFileError(InputFileError::Kind::CannotOpen, path,
                         fmt::format("cannot read the {} ({})", what, std::strerror(errno)));
  if (!S_ISREG(info.st_mode))
    throw InputFileError(InputFileError::Kind::NotRegular, path,
                         fmt::format("not a regular file ({}), so not read as the {}",
                                     S_ISDIR(info.st_mode)                            ? "a directory"
                                     : S_ISFIFO(info.st_mode)                         ? "a pipe"
                                     : S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode) ? "a device"
                                                                                      : "not a file of bytes",
                                     what));
  const auto tooLarge = [&] {
    return InputFileError(
        InputFileError::Kind::TooLarge, path,
        fmt::format("the {} is larger than {}, the most cbtl reads as one", what, describeBytes(maxBytes)));
  };
  if (static_cast<std::uintmax_t>(info.st_size) > maxBytes) throw tooLarge();
  ::fcntl(file.fd, F_SETFL, ::fcntl(file.fd, F_GETFL) & ~O_NONBLOCK);
  std::string text;
  text.reserve(static_cast<std::size_t>(info.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(file.fd, buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InputFileError(InputFileError::Kind::CannotOpen, path,
                           fmt::format("cannot read the {} ({})", what, std::strerror(errno)));
    }
    if (text.size() + static_cast<std::size_t>(n) > maxBytes) throw tooLarge();
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

}  // namespace cbtl::support
