#pragma once
// Numbers written as text, read strictly: the values of `--plant fmu:` options and the numeric
// attributes of modelDescription.xml. The whole text must be one number; nothing is skipped.

#include <optional>
#include <string_view>

namespace netmc::plant::fmu {

// [+-]? (digits [. digits?] | . digits) ([eE] [+-]? digits)?, within double's range (neither
// overflowing nor underflowing); nullopt otherwise (hexadecimal, "inf", "nan", blanks, trailing
// text, 1e999, 1e-999).
std::optional<double> parse_finite_decimal(std::string_view text);

// An xs:double of XML Schema (FMI 2.0, 2.2: the type of Real attributes): leading and trailing
// blanks allowed, and besides decimals the special values INF, -INF and NaN.
std::optional<double> parse_xml_double(std::string_view text);

// An xs:unsignedInt (a valueReference): decimal digits, at most 4294967295, blanks around allowed.
std::optional<unsigned int> parse_xml_unsigned(std::string_view text);

// An xs:boolean: true, false, 1 or 0, blanks around allowed.
std::optional<bool> parse_xml_boolean(std::string_view text);

}  // namespace netmc::plant::fmu
