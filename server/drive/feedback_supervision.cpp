#include "server/drive/feedback_supervision.hpp"

#include <fmt/format.h>

#include <bit>
#include <cmath>

namespace netmc::drive {
namespace {

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

}  // namespace

void FeedbackSupervision::begin() {
  previous_.reset();
  repeats_ = 0;
  seen_ = 0;
}

std::optional<std::string> FeedbackSupervision::check(const SupervisedSample& sample) {
  const double error = sample.reference_m - sample.position_m;
  std::optional<std::string> reason;
  if (!(std::abs(error) <= following_error_limit_m_)) {
    reason = fmt::format("following error {:.3g} mm beyond the {:g} mm limit at cycle {} (reference {:.6g} m, "
                         "actual {:.6g} m)",
                         error * 1e3, following_error_limit_m_ * 1e3, sample.cycle, sample.reference_m,
                         sample.position_m);
  }
  if (!reason) reason = jumped(sample);
  if (!reason && watch_frozen_) reason = frozen(sample);
  previous_ = sample;
  return reason;
}

std::optional<std::string> FeedbackSupervision::jumped(const SupervisedSample& sample) const {
  if (!previous_ || !std::isfinite(velocity_limit_m_s_)) return std::nullopt;
  const double elapsed_s = sample.time_s - previous_->read_start_s;
  const double step_m = std::abs(sample.position_m - previous_->position_m);
  const double allowed_m = velocity_limit_m_s_ * elapsed_s * (1.0 + kJumpMargin);
  if (step_m <= allowed_m) return std::nullopt;
  return fmt::format("feedback jumped {:.3g} mm within {:.3g} ms at cycle {}, more than the {:.3g} mm the velocity "
                     "limit {:g} m/s allows (with a {:g} % margin)",
                     step_m * 1e3, elapsed_s * 1e3, sample.cycle, allowed_m * 1e3, velocity_limit_m_s_,
                     kJumpMargin * 100.0);
}

std::optional<std::string> FeedbackSupervision::frozen(const SupervisedSample& sample) {
  const bool repeated = previous_ && same_bits(sample.position_m, previous_->position_m) &&
                        same_bits(sample.velocity_m_s, previous_->velocity_m_s);
  repeats_ = repeated ? repeats_ + 1 : 1;
  const std::size_t slot = seen_ % kFrozenSamples;
  recent_reference_m_[slot] = sample.reference_m;
  recent_job_time_s_[slot] = sample.job_time_s;
  recent_time_s_[slot] = sample.time_s;
  ++seen_;
  if (repeats_ < kFrozenSamples) return std::nullopt;
  // The oldest of the last kFrozenSamples samples is the next slot to be written.
  const std::size_t oldest = seen_ % kFrozenSamples;
  const double moved_m = std::abs(sample.reference_m - recent_reference_m_[oldest]);
  const double span_s = sample.job_time_s - recent_job_time_s_[oldest];
  if (!(moved_m > kFrozenReferenceSpeedMS * span_s)) return std::nullopt;
  // Reads that came in a burst (a node catching up after a stall) may repeat a moving encoder's
  // count: only readings the drive latched at least half the samples' span apart count.
  if (sample.read_start_s - recent_time_s_[oldest] < 0.5 * span_s) return std::nullopt;
  return fmt::format("feedback frozen: position {:.7g} m unchanged for {} samples while the reference moved {:.3g} mm "
                     "(cycle {})",
                     sample.position_m, repeats_, moved_m * 1e3, sample.cycle);
}

}  // namespace netmc::drive
