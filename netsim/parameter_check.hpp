#pragma once
// Validation of user-supplied model parameters (job specs, CLI flags, trace files).
// Each check throws std::invalid_argument naming the model, the parameter and the expected
// form, so a bad delay profile fails at construction instead of producing silent garbage.

#include <cstddef>
#include <string_view>

namespace netmc::netsim {

// The longest delay a parameter or trace sample may state: a minute, far beyond any loop
// (a delay this long is a lost message), and a bound on what a job keeps in flight.
inline constexpr double kMaxDelayS = 60.0;
// The most samples a delay trace may hold (8 MB of doubles).
inline constexpr std::size_t kMaxDelayTraceSamples = 1'000'000;

// value_s must be finite, >= 0 and <= kMaxDelayS (a delay in seconds).
void require_delay(std::string_view model, std::string_view name, double value_s);

// value_s must be >= lower_s (lower_s already checked) and not NaN; +inf is allowed.
void require_upper_bound(std::string_view model, std::string_view name, double value_s,
                         std::string_view lower_name, double lower_s);

// p must be a probability in [0, 1].
void require_probability(std::string_view model, std::string_view name, double p);

// value must be finite and > 0 (dimensionless, e.g. a shape parameter).
void require_positive(std::string_view model, std::string_view name, double value);

}  // namespace netmc::netsim
