#pragma once
// What each sample of a job's iteration must satisfy against the job's reference for the axis,
// beside the operator's static limits (SupervisedAxis): the axis follows its reference within the
// following-error limit, and its feedback is plausible. A frozen encoder repeats position and
// velocity bit for bit while the reference moves on; a jumping one steps further between two
// samples than the velocity limit allows in the time between them. Each check names the first
// sample that breaks it; the caller trips the axis with that text.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace netmc::drive {

struct SupervisedSample {
  std::uint64_t cycle = 0;  // the job's cycle k (named in a trip)
  double job_time_s = 0.0;  // its instant t_k, where the reference was taken
  double time_s = 0.0;      // when the drive's answer was in (s, any origin)
  double reference_m = 0.0;  // the job's reference for this axis at the sample's instant
  double position_m = 0.0;
  double velocity_m_s = 0.0;
  // When the read was asked for (same origin; time_s for a drive read at once): the drive
  // latched the previous reading after the previous sample's read_start_s and this one before
  // time_s, so a jump is judged over the longest that can have passed between the two (a node
  // that stalls between the two halves of an exchange then catches up does not make a step).
  double read_start_s = 0.0;
};

class FeedbackSupervision {
 public:
  // Identical samples in a row that make a frozen encoder (the third trips).
  static constexpr std::size_t kFrozenSamples = 3;
  // Frozen only while the reference moves faster than this over those samples: a resting or
  // creeping axis repeats its reading legitimately (an encoder count is far below 20 mm/s x 10 ms
  // = 0.2 mm at h = 5 ms, and a friction-held axis breaks away long before its reference at this
  // speed is a tenth of a millimetre ahead).
  static constexpr double kFrozenReferenceSpeedMS = 0.02;
  // A step between samples beyond velocity limit x elapsed time x (1 + margin) is a jump; the
  // margin covers when, within its exchange, the drive latched each reading.
  static constexpr double kJumpMargin = 0.5;

  // Infinite limits leave their check out; `watch_frozen` false leaves out the frozen check (a
  // simulated drive reads its model, which has no encoder to freeze and may rest bit for bit,
  // held by friction).
  FeedbackSupervision(double following_error_limit_m, double velocity_limit_m_s, bool watch_frozen = true)
      : following_error_limit_m_(following_error_limit_m),
        velocity_limit_m_s_(velocity_limit_m_s),
        watch_frozen_(watch_frozen) {}

  // An iteration starts: no sample before it counts.
  void begin();
  // Why `sample` trips the axis ("following error 2.31 mm beyond the 2 mm limit at cycle 812"),
  // nullopt if it does not.
  std::optional<std::string> check(const SupervisedSample& sample);

 private:
  std::optional<std::string> frozen(const SupervisedSample& sample);
  std::optional<std::string> jumped(const SupervisedSample& sample) const;

  double following_error_limit_m_;
  double velocity_limit_m_s_;
  bool watch_frozen_;
  std::optional<SupervisedSample> previous_;
  std::size_t repeats_ = 0;  // samples in a row with this position and velocity, bit for bit
  // The reference at the last kFrozenSamples samples (a ring), for how far it moved over them.
  double recent_reference_m_[kFrozenSamples] = {};
  double recent_job_time_s_[kFrozenSamples] = {};
  double recent_time_s_[kFrozenSamples] = {};
  std::size_t seen_ = 0;
};

}  // namespace netmc::drive
