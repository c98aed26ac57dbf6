#include "server/management/access_token.hpp"

#include <sys/random.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace netmc::management {

AccessToken AccessToken::from_file(const std::string& path) {
  std::ifstream file(path);
  std::string line;
  if (!file || !std::getline(file, line)) {
    throw std::invalid_argument("token file " + path + ": cannot read a line from it");
  }
  const auto first = line.find_first_not_of(" \t\r");
  const auto last = line.find_last_not_of(" \t\r");
  const std::string token = first == std::string::npos ? "" : line.substr(first, last - first + 1);
  bool printable = true;
  for (const char c : token) printable = printable && c > ' ' && c < 0x7f;
  if (token.size() < 16 || token.size() > 4096 || !printable) {
    throw std::invalid_argument("token file " + path +
                                ": expected one line of 16 to 4096 printable characters without spaces");
  }
  return AccessToken(token);
}

AccessToken AccessToken::random() {
  unsigned char bytes[32];
  std::size_t filled = 0;
  while (filled < sizeof bytes) {
    const ssize_t got = ::getrandom(bytes + filled, sizeof bytes - filled, 0);
    if (got < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("getrandom: ") + std::strerror(errno));
    }
    filled += static_cast<std::size_t>(got);
  }
  constexpr char kDigits[] = "0123456789abcdef";
  std::string value;
  for (const unsigned char byte : bytes) {
    value += kDigits[byte >> 4];
    value += kDigits[byte & 0xf];
  }
  return AccessToken(value);
}

bool AccessToken::accepts(const std::string& presented) const {
  // Every byte of the token is looked at whatever the presented text is.
  unsigned char difference = presented.size() == value_.size() ? 0 : 1;
  for (std::size_t i = 0; i < value_.size(); ++i) {
    const char other = i < presented.size() ? presented[i] : '\0';
    difference |= static_cast<unsigned char>(value_[i] ^ other);
  }
  return difference == 0;
}

std::optional<AccessToken> client_token_from_environment() {
  const char* path = std::getenv("NETMC_TOKEN_FILE");
  if (!path || !*path) return std::nullopt;
  return AccessToken::from_file(path);
}

}  // namespace netmc::management
