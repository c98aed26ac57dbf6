// Normal delay restricted to [min, max]: jitter around a nominal latency that can never be
// negative or exceed a physical bound.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "netsim/delay_model.hpp"
#include "netsim/parameter_check.hpp"
#include "netsim/text_format.hpp"

namespace netmc::netsim {

namespace {

// Enough for any window holding a few percent of the mass; beyond that clamping is cheaper
// than an unbounded loop and its bias is negligible for such a degenerate window.
constexpr int kMaxRejectionTries = 64;

double standard_normal_density(double x) {
  return std::exp(-0.5 * x * x) / std::sqrt(2.0 * std::numbers::pi);
}

// Upper tail Q(x) = P(Z > x); erfc keeps precision far out in the tail.
double standard_normal_upper_tail(double x) { return 0.5 * std::erfc(x / std::numbers::sqrt2); }

double truncated_normal_mean(double mean, double stddev, double min, double max) {
  if (stddev == 0.0) return std::clamp(mean, min, max);
  const double alpha = (min - mean) / stddev;
  const double beta = (max - mean) / stddev;  // may be +inf
  // Mass of [alpha, beta], computed from the side that avoids cancellation.
  const double mass = alpha > 0.0
                          ? standard_normal_upper_tail(alpha) - standard_normal_upper_tail(beta)
                          : standard_normal_upper_tail(-beta) - standard_normal_upper_tail(-alpha);
  // No representable mass: every draw ends up clamped to the bound nearest the mean.
  if (!(mass > 0.0)) return std::clamp(mean, min, max);
  const double mean_shift =
      stddev * (standard_normal_density(alpha) - standard_normal_density(beta)) / mass;
  return std::clamp(mean + mean_shift, min, max);
}

class TruncatedNormalDelay final : public DelayModel {
 public:
  TruncatedNormalDelay(double mean_s, double stddev_s, double min_s, double max_s)
      : mean_s_(mean_s),
        stddev_s_(stddev_s),
        min_s_(min_s),
        max_s_(max_s),
        truncated_mean_s_(truncated_normal_mean(mean_s, stddev_s, min_s, max_s)) {}

  double next_delay_s(RandomStream& rng) override {
    double draw = mean_s_ + stddev_s_ * rng.standard_normal();
    for (int tries = 1; tries < kMaxRejectionTries && (draw < min_s_ || draw > max_s_); ++tries) {
      draw = mean_s_ + stddev_s_ * rng.standard_normal();
    }
    return std::clamp(draw, min_s_, max_s_);
  }

  std::unique_ptr<DelayModel> clone() const override {
    return std::make_unique<TruncatedNormalDelay>(mean_s_, stddev_s_, min_s_, max_s_);
  }

  std::string describe() const override {
    return "truncated_normal(mean " + format_duration(mean_s_) + ", stddev " + format_duration(stddev_s_) +
           ", [" + format_duration(min_s_) + ", " + format_duration(max_s_) + "])";
  }

  double mean_s() const override { return truncated_mean_s_; }

 private:
  double mean_s_;
  double stddev_s_;
  double min_s_;
  double max_s_;
  double truncated_mean_s_;
};

}  // namespace

std::unique_ptr<DelayModel> make_truncated_normal_delay(double mean_s, double stddev_s, double min_s,
                                                        double max_s) {
  constexpr const char* model = "truncated normal delay";
  require_delay(model, "mean", mean_s);
  require_delay(model, "stddev", stddev_s);
  require_delay(model, "min", min_s);
  require_upper_bound(model, "max", max_s, "min", min_s);
  return std::make_unique<TruncatedNormalDelay>(mean_s, stddev_s, min_s, max_s);
}

}  // namespace netmc::netsim
