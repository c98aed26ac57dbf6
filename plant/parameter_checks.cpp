#include "plant/parameter_checks.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace netmc::plant {
namespace {

[[noreturn]] void fail(std::string_view owner, std::string_view name, std::string_view expected,
                       double value) {
  std::ostringstream out;
  out << owner << ": " << name << " must be " << expected << " (got " << value << ")";
  throw std::invalid_argument(out.str());
}

}  // namespace

void require_finite(std::string_view owner, std::string_view name, double value) {
  if (!std::isfinite(value)) fail(owner, name, "a finite number", value);
}

void require_positive(std::string_view owner, std::string_view name, double value) {
  if (!std::isfinite(value) || !(value > 0.0)) fail(owner, name, "a finite number > 0", value);
}

void require_non_negative(std::string_view owner, std::string_view name, double value) {
  if (!std::isfinite(value) || !(value >= 0.0)) fail(owner, name, "a finite number >= 0", value);
}

void require_advance_arguments(std::string_view owner, double duration_s, double input) {
  require_non_negative(owner, "duration_s", duration_s);
  require_finite(owner, "input", input);
}

long long substep_count(std::string_view owner, double duration_s, double max_substep_s) {
  const double ratio = duration_s / max_substep_s;
  // 2^40 sub-steps would take hours; beyond that the count no longer fits the loop sensibly.
  constexpr double kMaxSubsteps = 1099511627776.0;
  if (!(ratio <= kMaxSubsteps)) {
    std::ostringstream out;
    out << owner << ": duration_s / max_substep_s must be <= 2^40 sub-steps (got " << duration_s
        << " s / " << max_substep_s << " s)";
    throw std::invalid_argument(out.str());
  }
  // ceil(duration / max_substep), ignoring a few ulp of round-off so that e.g. 5e-3 / 1e-4 gives
  // 50 sub-steps and not 51.
  const double n = std::ceil(ratio * (1.0 - 1e-12));
  return n < 1.0 ? 1LL : static_cast<long long>(n);
}

}  // namespace netmc::plant
