#pragma once
// Text that came from an FMU (its description, its log messages, the loader's dlerror about it)
// made safe to show an operator: at most `max_length` characters, printable ASCII kept, anything
// else (control characters, escape sequences, UTF-8 bytes) shown as '?', and "..." where it was
// cut.

#include <cstddef>
#include <string>
#include <string_view>

namespace netmc::plant::fmu {

std::string printable_text(std::string_view text, std::size_t max_length = 200);

// The same text between single quotes, for naming a value in a message.
std::string quoted(std::string_view text, std::size_t max_length = 80);

}  // namespace netmc::plant::fmu
