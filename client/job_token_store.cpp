#include "client/job_token_store.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "server/management/access_token.hpp"

namespace netmc::cli {
namespace {

std::optional<std::filesystem::path> job_token_directory() {
  // XDG: a relative $XDG_STATE_HOME is to be ignored.
  if (const char* state = std::getenv("XDG_STATE_HOME"); state && state[0] == '/') {
    return std::filesystem::path(state) / "netmc" / "jobs";
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return std::filesystem::path(home) / ".local" / "state" / "netmc" / "jobs";
  }
  return std::nullopt;
}

// Creates `directory` and its missing parents 0700; `directory` itself must end up a real
// directory of this user that no one else can enter.
void make_private_directory(const std::filesystem::path& directory) {
  const auto fail = [&](const std::string& why) {
    throw std::runtime_error("job token directory " + directory.string() + ": " + why);
  };
  std::filesystem::path partial;
  for (const auto& part : directory) {
    partial /= part;
    if (::mkdir(partial.c_str(), 0700) != 0 && errno != EEXIST) fail(std::strerror(errno));
  }
  struct stat info {};
  if (::lstat(directory.c_str(), &info) != 0) fail(std::strerror(errno));
  if (!S_ISDIR(info.st_mode) || info.st_uid != ::getuid()) fail("not a directory of this user");
  if ((info.st_mode & 077) != 0 && ::chmod(directory.c_str(), 0700) != 0) fail(std::strerror(errno));
}

}  // namespace

std::optional<std::filesystem::path> job_token_path(const std::string& server, std::uint64_t job_id) {
  const auto directory = job_token_directory();
  if (!directory) return std::nullopt;
  // The address as a file name: "127.0.0.1:7300" -> "127.0.0.1_7300".
  std::string name;
  for (const char c : server) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '-';
    name += plain ? c : '_';
  }
  return *directory / (name + "-job-" + std::to_string(job_id) + ".token");
}

std::filesystem::path save_job_token(const std::string& server, std::uint64_t job_id, const std::string& token) {
  // The token comes from the server: keep only what a netmc-server sends (hex, 16-256 characters),
  // never a long or multi-line text into the user's files.
  const bool plain_hex = token.size() >= 16 && token.size() <= 256 &&
                         token.find_first_not_of("0123456789abcdefABCDEF") == std::string::npos;
  if (!plain_hex) {
    throw std::runtime_error("the server's cancel token is not 16-256 hexadecimal characters (" +
                             std::to_string(token.size()) + " bytes): not kept");
  }
  const auto path = job_token_path(server, job_id);
  if (!path) throw std::runtime_error("job token: neither XDG_STATE_HOME nor HOME is set");
  make_private_directory(path->parent_path());
  const auto fail = [&] { throw std::runtime_error("job token file " + path->string() + ": " + std::strerror(errno)); };
  const int fd = ::open(path->c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) fail();
  const std::string line = token + "\n";
  const bool written = ::fchmod(fd, 0600) == 0 &&
                       ::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size());
  const int saved_errno = errno;
  ::close(fd);
  errno = saved_errno;
  if (!written) fail();
  return *path;
}

std::optional<std::string> saved_job_token(const std::string& server, std::uint64_t job_id) {
  const auto path = job_token_path(server, job_id);
  if (!path || !std::filesystem::exists(*path)) return std::nullopt;
  return management::AccessToken::from_file(path->string()).value();
}

bool forget_job_token(const std::string& server, std::uint64_t job_id) {
  const auto path = job_token_path(server, job_id);
  std::error_code error;
  return path && std::filesystem::remove(*path, error);
}

}  // namespace netmc::cli
