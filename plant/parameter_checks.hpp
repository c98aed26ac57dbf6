#pragma once
// Parameter validation shared by the plant models: a bad value throws std::invalid_argument naming
// the owner, the parameter and the expected form, so a wrong job spec fails loudly and early.

#include <string_view>

namespace netmc::plant {

// finite (not NaN, not +-inf)
void require_finite(std::string_view owner, std::string_view name, double value);
// finite and > 0
void require_positive(std::string_view owner, std::string_view name, double value);
// finite and >= 0
void require_non_negative(std::string_view owner, std::string_view name, double value);
// Arguments of AxisPlant::advance: finite duration >= 0 and a finite input.
void require_advance_arguments(std::string_view owner, double duration_s, double input);
// Number of integration sub-steps ceil(duration / max_substep); throws if absurdly many.
long long substep_count(std::string_view owner, double duration_s, double max_substep_s);

}  // namespace netmc::plant
