#include "server/store/state_directory_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <string>
#include <system_error>

#include <spdlog/spdlog.h>

#include "server/store/job_store.hpp"

namespace netmc::store {
namespace {

std::string errno_text() { return std::system_category().message(errno); }

// The pid the holder wrote, or "" when the file holds no plain number (a pid is all it should hold;
// the text goes into a message, so nothing else of it is shown).
std::string holder_pid(int fd) {
  std::array<char, 24> text{};
  const ssize_t n = ::pread(fd, text.data(), text.size() - 1, 0);
  if (n <= 0) return "";
  std::string pid(text.data(), static_cast<std::size_t>(n));
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  if (pid.empty() || pid.size() > 10 || pid.find_first_not_of("0123456789") != std::string::npos) return "";
  return pid;
}

}  // namespace

StateDirectoryLock::StateDirectoryLock(const std::filesystem::path& directory) {
  const auto file = directory / kFileName;
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd_ < 0) throw StoreError("cannot open " + file.string() + ": " + errno_text());
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int cause = errno;
    const std::string pid = holder_pid(fd_);
    ::close(fd_);
    fd_ = -1;
    if (cause == EWOULDBLOCK) {
      throw StoreError(directory.string() + " is the job store of another netmc-server" +
                       (pid.empty() ? std::string() : " (pid " + pid + ")") + ", which holds " + file.string() +
                       ": stop it, or give this server another --state-dir");
    }
    throw StoreError("cannot lock " + file.string() + ": " + std::system_category().message(cause));
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  // The lock is what excludes; the pid only names the holder in another server's refusal.
  const bool written = ::ftruncate(fd_, 0) == 0 &&
                       ::pwrite(fd_, pid.data(), pid.size(), 0) == static_cast<ssize_t>(pid.size());
  if (!written) spdlog::warn("{}: cannot write this server's pid: {}", file.string(), errno_text());
}

StateDirectoryLock::~StateDirectoryLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

}  // namespace netmc::store
