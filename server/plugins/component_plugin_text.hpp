#pragma once
// Text that comes from a plugin (its version field, describe(), an exception's what()), made safe
// to log and to show an operator: read up to the first NUL or `size` bytes (never past them),
// printable ASCII kept, anything else (control characters, escape sequences, UTF-8 bytes) shown
// as '?', surrounding blanks trimmed, and at most kMaxPluginTextLength characters kept.

#include <cstddef>
#include <string>
#include <string_view>

namespace netmc::plugins {

inline constexpr std::size_t kMaxPluginTextLength = 512;

// `fallback` when nothing printable is left.
std::string plugin_text(const char* text, std::size_t size, std::string_view fallback);
std::string plugin_text(std::string_view text, std::string_view fallback);

}  // namespace netmc::plugins
