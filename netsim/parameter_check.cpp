#include "netsim/parameter_check.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "netsim/text_format.hpp"

namespace netmc::netsim {

namespace {

[[noreturn]] void fail(std::string_view model, std::string_view name, std::string_view expectation,
                       const std::string& got) {
  std::string message(model);
  message.append(": ").append(name).append(" must be ").append(expectation);
  message.append(" (got ").append(got).append(")");
  throw std::invalid_argument(message);
}

std::string assignment(std::string_view name, const std::string& value_text) {
  return std::string(name) + "=" + value_text;
}

}  // namespace

void require_delay(std::string_view model, std::string_view name, double value_s) {
  if (std::isfinite(value_s) && value_s >= 0.0 && value_s <= kMaxDelayS) return;
  fail(model, name, "a delay in [0, " + format_number(kMaxDelayS) + "] s", assignment(name, format_number(value_s) + " s"));
}

void require_upper_bound(std::string_view model, std::string_view name, double value_s,
                         std::string_view lower_name, double lower_s) {
  if (!std::isnan(value_s) && value_s >= lower_s) return;
  fail(model, name, std::string(">= ") + std::string(lower_name) + " (+inf allowed)",
       assignment(lower_name, format_number(lower_s) + " s") + ", " +
           assignment(name, format_number(value_s) + " s"));
}

void require_probability(std::string_view model, std::string_view name, double p) {
  if (p >= 0.0 && p <= 1.0) return;  // false for NaN as well
  fail(model, name, "a probability in [0, 1]", assignment(name, format_number(p)));
}

void require_positive(std::string_view model, std::string_view name, double value) {
  if (std::isfinite(value) && value > 0.0) return;
  fail(model, name, "a finite number > 0", assignment(name, format_number(value)));
}

}  // namespace netmc::netsim
