#pragma once
// Framing of the management endpoint: a 4-byte big-endian length, then a serialized protobuf
// message. The decoder takes bytes as they come off the socket and yields whole frames.

#include <google/protobuf/message_lite.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

namespace netmc::management {

inline constexpr std::uint32_t kMaxFrameBytes = 16u << 20;  // 16 MiB

class FrameError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::string encode_frame(const google::protobuf::MessageLite& message);

class FrameDecoder {
 public:
  void feed(const char* data, std::size_t size);
  // The payload of the next complete frame; throws FrameError for an oversize length.
  std::optional<std::string> next();

 private:
  std::string buffer_;
};

}  // namespace netmc::management
