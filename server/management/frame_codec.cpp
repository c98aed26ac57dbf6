#include "server/management/frame_codec.hpp"

namespace netmc::management {

std::string encode_frame(const google::protobuf::MessageLite& message) {
  const std::string payload = message.SerializeAsString();
  if (payload.size() > kMaxFrameBytes) throw FrameError("frame: message larger than 16 MiB");
  const auto size = static_cast<std::uint32_t>(payload.size());
  std::string frame;
  frame.reserve(4 + payload.size());
  for (int shift = 24; shift >= 0; shift -= 8) frame.push_back(static_cast<char>((size >> shift) & 0xFF));
  frame += payload;
  return frame;
}

void FrameDecoder::feed(const char* data, std::size_t size) { buffer_.append(data, size); }

std::optional<std::string> FrameDecoder::next() {
  if (buffer_.size() < 4) return std::nullopt;
  std::uint32_t size = 0;
  for (int i = 0; i < 4; ++i) size = (size << 8) | static_cast<unsigned char>(buffer_[static_cast<std::size_t>(i)]);
  if (size > kMaxFrameBytes) {
    throw FrameError("frame: length " + std::to_string(size) + " exceeds the 16 MiB limit");
  }
  if (buffer_.size() < 4 + static_cast<std::size_t>(size)) return std::nullopt;
  std::string payload = buffer_.substr(4, size);
  buffer_.erase(0, 4 + static_cast<std::size_t>(size));
  return payload;
}

}  // namespace netmc::management
