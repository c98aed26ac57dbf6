#pragma once
// The shared secret that a management client shows with every request when the server was
// started with --token-file. Read from a file (never from the command line, where `ps` shows
// it); compared in constant time.

#include <optional>
#include <string>

namespace netmc::management {

class AccessToken {
 public:
  // The first line of `path`, without surrounding whitespace: 16 to 4096 printable characters.
  // Throws std::invalid_argument naming the file otherwise (or when it cannot be read).
  static AccessToken from_file(const std::string& path);

  // 256 bits from the kernel's CSPRNG (getrandom) as 64 hex digits: a job's cancel token.
  static AccessToken random();

  // Constant time in the length of the token: a wrong guess learns nothing from the timing.
  bool accepts(const std::string& presented) const;
  const std::string& value() const { return value_; }

 private:
  explicit AccessToken(std::string value) : value_(std::move(value)) {}
  std::string value_;
};

// The token a client shows: from the file named by $NETMC_TOKEN_FILE, if set.
std::optional<AccessToken> client_token_from_environment();

}  // namespace netmc::management
