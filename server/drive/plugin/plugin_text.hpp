#pragma once
// Text a plugin wrote into one of netmc's buffers, made safe to log and to show an operator:
// read up to the first NUL or the buffer's end (never past it), printable ASCII kept, anything
// else (control characters, escape sequences, UTF-8 bytes) shown as '?', surrounding blanks
// trimmed.

#include <cstddef>
#include <string>

namespace netmc::drive {

// `fallback` when the plugin wrote nothing printable.
std::string plugin_text(const char* buffer, std::size_t size, const char* fallback);

}  // namespace netmc::drive
