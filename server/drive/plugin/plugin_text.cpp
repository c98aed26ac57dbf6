#include "server/drive/plugin/plugin_text.hpp"

namespace netmc::drive {

std::string plugin_text(const char* buffer, std::size_t size, const char* fallback) {
  std::string text;
  for (std::size_t i = 0; i < size && buffer[i] != '\0'; ++i) {
    const char c = buffer[i];
    text.push_back(c >= 0x20 && c <= 0x7E ? c : '?');
  }
  const std::size_t first = text.find_first_not_of(' ');
  if (first == std::string::npos) return fallback;
  return text.substr(first, text.find_last_not_of(' ') - first + 1);
}

}  // namespace netmc::drive
