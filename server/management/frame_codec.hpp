#pragma once
// Framing of the management endpoint: a 4-byte big-endian unsigned length, then a serialized
// protobuf message. The decoder takes bytes as they come off the socket and yields whole frames.
// Pure: no sockets, no threads.

#include <google/protobuf/message_lite.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

namespace netmc::management {

inline constexpr std::uint32_t kMaxFrameBytes = 16u << 20;  // 16 MiB of payload
inline constexpr std::size_t kFrameHeaderBytes = 4;

// A frame that cannot be encoded or decoded (oversize length, unparsable payload).
class FrameError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The 4-byte length followed by the serialized message; throws FrameError above 16 MiB.
std::string encode_frame(const google::protobuf::MessageLite& message);

class FrameDecoder {
 public:
  // Appends bytes in any split: part of a frame, one frame, several frames.
  void feed(const char* data, std::size_t size);
  // The payload of the next complete frame, nullopt until one is complete; throws FrameError
  // when the next length exceeds kMaxFrameBytes (the stream cannot be resynchronized after it).
  std::optional<std::string> next();
  // Bytes fed but not yet returned by next().
  std::size_t buffered() const { return buffer_.size() - start_; }

 private:
  std::string buffer_;
  std::size_t start_ = 0;  // first byte of the next frame in buffer_
};

}  // namespace netmc::management
