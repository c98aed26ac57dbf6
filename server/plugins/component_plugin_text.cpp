#include "server/plugins/component_plugin_text.hpp"

namespace netmc::plugins {

std::string plugin_text(const char* text, std::size_t size, std::string_view fallback) {
  std::string shown;
  std::size_t i = 0;
  for (; i < size && text[i] != '\0' && shown.size() < kMaxPluginTextLength; ++i) {
    const char c = text[i];
    shown.push_back(c >= 0x20 && c <= 0x7E ? c : '?');
  }
  const bool cut = shown.size() == kMaxPluginTextLength && i < size && text[i] != '\0';
  const std::size_t first = shown.find_first_not_of(' ');
  if (first == std::string::npos) return std::string(fallback);
  shown = shown.substr(first, shown.find_last_not_of(' ') - first + 1);
  return cut ? shown + "..." : shown;
}

std::string plugin_text(std::string_view text, std::string_view fallback) {
  return plugin_text(text.data(), text.size(), fallback);
}

}  // namespace netmc::plugins
