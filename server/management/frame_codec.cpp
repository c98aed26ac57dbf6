#include "server/management/frame_codec.hpp"

namespace netmc::management {

std::string encode_frame(const google::protobuf::MessageLite& message) {
  const std::size_t size = message.ByteSizeLong();
  if (size > kMaxFrameBytes) {
    throw FrameError("frame: message of " + std::to_string(size) + " bytes exceeds the 16 MiB limit");
  }
  const auto length = static_cast<std::uint32_t>(size);
  std::string frame;
  frame.reserve(kFrameHeaderBytes + size);
  for (int shift = 24; shift >= 0; shift -= 8) {
    frame.push_back(static_cast<char>((length >> shift) & 0xFFu));
  }
  if (!message.AppendToString(&frame)) throw FrameError("frame: cannot serialize the message");
  return frame;
}

void FrameDecoder::feed(const char* data, std::size_t size) {
  if (start_ > 0 && start_ == buffer_.size()) {  // everything consumed: start over cheaply
    buffer_.clear();
    start_ = 0;
  }
  buffer_.append(data, size);
}

std::optional<std::string> FrameDecoder::next() {
  if (buffered() < kFrameHeaderBytes) return std::nullopt;
  std::uint32_t length = 0;
  for (std::size_t i = 0; i < kFrameHeaderBytes; ++i) {
    length = (length << 8) | static_cast<unsigned char>(buffer_[start_ + i]);
  }
  if (length > kMaxFrameBytes) {
    throw FrameError("frame: length " + std::to_string(length) + " exceeds the 16 MiB limit");
  }
  if (buffered() < kFrameHeaderBytes + length) return std::nullopt;
  std::string payload = buffer_.substr(start_ + kFrameHeaderBytes, length);
  start_ += kFrameHeaderBytes + length;
  if (start_ >= buffer_.size() / 2) {  // drop consumed bytes once they are half the buffer
    buffer_.erase(0, start_);
    start_ = 0;
  }
  return payload;
}

}  // namespace netmc::management
