#include "client/exclusive_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>
#include <system_error>

namespace netmc::cli {
namespace {

// mkstemp's file, opened; -1 on failure.
int open_exclusive(const std::filesystem::path& target, std::string& name) {
  name = target.string() + ".XXXXXX";
  const int fd = mkostemp(name.data(), O_CLOEXEC);
  if (fd >= 0 && fchmod(fd, 0644) != 0) {
    close(fd);
    unlink(name.c_str());
    return -1;
  }
  return fd;
}

}  // namespace

std::filesystem::path create_exclusive_temporary(const std::filesystem::path& target) {
  std::string name;
  const int fd = open_exclusive(target, name);
  if (fd < 0) throw std::runtime_error(target.string() + ": cannot create a temporary file beside it");
  close(fd);
  return name;
}

void write_file_atomically(const std::string& path, const std::string& content) {
  std::string name;
  const int fd = open_exclusive(path, name);
  if (fd < 0) throw std::runtime_error(path + ": cannot open for writing");
  std::size_t written = 0;
  bool ok = true;
  while (ok && written < content.size()) {
    const ssize_t n = write(fd, content.data() + written, content.size() - written);
    if (n < 0 && errno == EINTR) continue;
    ok = n > 0;
    if (ok) written += static_cast<std::size_t>(n);
  }
  ok = (close(fd) == 0) && ok;
  std::error_code error;
  if (ok) std::filesystem::rename(name, path, error);
  if (!ok || error) {
    std::filesystem::remove(name, error);
    throw std::runtime_error(path + (ok ? ": cannot rename into place" : ": cannot write"));
  }
}

}  // namespace netmc::cli
