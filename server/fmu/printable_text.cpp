#include "server/fmu/printable_text.hpp"

namespace netmc::plant::fmu {

std::string printable_text(std::string_view text, std::size_t max_length) {
  const bool cut = text.size() > max_length;
  std::string out;
  out.reserve(cut ? max_length + 3 : text.size());
  for (std::size_t i = 0; i < text.size() && i < max_length; ++i) {
    const char c = text[i];
    out.push_back(c >= 0x20 && c <= 0x7E ? c : '?');
  }
  if (cut) out += "...";
  return out;
}

std::string quoted(std::string_view text, std::size_t max_length) {
  std::string out = "'";
  out += printable_text(text, max_length);
  out += '\'';
  return out;
}

}  // namespace netmc::plant::fmu
