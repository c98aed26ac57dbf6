#pragma once
// The compact text of flags and descriptors: quantities with unit suffixes (SI unless a suffix
// s, ms, us, m, mm, um, m/s, mm/s, m/s2 is given) and `key=value,...` lists. Errors are
// std::invalid_argument naming the field and the expected form.

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace netmc::job {

enum class Quantity { length, time, speed, acceleration, plain };

std::string_view trim(std::string_view text);

// "a,b,,c" -> {"a", "b", "c"} (empty items dropped).
std::vector<std::string> split_list(const std::string& text);
// {"a", "b"} -> "a, b" (with separator ", ").
std::string join_list(const std::vector<std::string>& words, const char* separator = ", ");

// "10mm" -> 0.01 (length), "0.5ms" -> 5e-4 (time), "20mm/s" -> 0.02 (speed),
// "0.5m/s2" -> 0.5 (acceleration; also m/s^2, mm/s2), "3" -> 3 (SI). `field` names the flag/key.
double parse_quantity(std::string_view text, Quantity quantity, std::string_view field);

// Parses "a=1,b=2" and checks every key is allowed (and given once). The value of a key in
// `list_keys` may contain commas itself ("points=0,0;1mm,0"): the items without '=' that follow
// it belong to it.
std::map<std::string, std::string> parse_keys(std::string_view text, std::string_view field,
                                              const std::vector<std::string>& allowed,
                                              const std::vector<std::string>& list_keys = {});

}  // namespace netmc::job
