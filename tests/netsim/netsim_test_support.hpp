#pragma once
// Shared helpers for the netsim tests: sample statistics, draw loops and a check that an
// action throws std::invalid_argument with a message naming the offending parameter.

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "netsim/delay_model.hpp"
#include "netsim/random_stream.hpp"

namespace netmc::netsim::test {

// Large enough that 5-sigma bounds are tight (well under 1 % of the mean for these models).
inline constexpr int kSampleCount = 200000;

struct SampleMoments {
  double mean;
  double variance;  // unbiased
};

inline SampleMoments sample_moments(const std::vector<double>& samples) {
  double sum = 0.0;
  for (const double x : samples) sum += x;
  const double mean = sum / static_cast<double>(samples.size());
  double squares = 0.0;
  for (const double x : samples) squares += (x - mean) * (x - mean);
  return {mean, squares / static_cast<double>(samples.size() - 1)};
}

inline std::vector<double> draw_delays(DelayModel& model, RandomStream& rng, int count) {
  std::vector<double> delays;
  delays.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) delays.push_back(model.next_delay_s(rng));
  return delays;
}

// Standard normal CDF from std::erf, as independent truth for the truncated-normal model.
inline double normal_cdf(double x) { return 0.5 * (1.0 + std::erf(x / std::sqrt(2.0))); }
inline double normal_pdf(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2.0 * std::numbers::pi); }

template <typename Action>
void expect_invalid_argument(Action&& action, std::initializer_list<std::string_view> message_fragments) {
  try {
    action();
    ADD_FAILURE() << "expected std::invalid_argument, nothing was thrown";
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    for (const std::string_view fragment : message_fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "message \"" << message << "\" lacks \"" << fragment << "\"";
    }
  } catch (const std::exception& error) {
    ADD_FAILURE() << "expected std::invalid_argument, got another exception: " << error.what();
  }
}

}  // namespace netmc::netsim::test
