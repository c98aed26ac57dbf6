#include "server/fmu/private_directory.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace netmc::plant::fmu {
namespace {

std::string temporary_root() {
  const char* tmpdir = std::getenv("TMPDIR");
  if (tmpdir != nullptr && tmpdir[0] == '/') return tmpdir;
  return "/tmp";
}

}  // namespace

PrivateDirectory::PrivateDirectory() {
  std::string pattern = temporary_root() + "/netmc-fmu-XXXXXX";
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  // mkdtemp creates the directory with mode 0700 under a name no other process can have taken.
  if (::mkdtemp(buffer.data()) == nullptr) {
    throw std::runtime_error("fmu: cannot make a private directory as " + pattern + ": " + std::strerror(errno));
  }
  path_ = buffer.data();
}

PrivateDirectory::~PrivateDirectory() {
  // remove_all removes a symbolic link itself, not what it points to; errors are left (a
  // destructor cannot report them, and what remains is in a 0700 directory).
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::string PrivateDirectory::entry(std::string_view name) const { return path_ + "/" + std::string(name); }

}  // namespace netmc::plant::fmu
