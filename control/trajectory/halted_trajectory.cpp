#include "control/trajectory/halted_trajectory.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace netmc::control {

HaltedTrajectory::HaltedTrajectory(std::shared_ptr<const ReferenceTrajectory> motion,
                                   double halt_at_s, double halt_duration_s)
    : motion_(std::move(motion)), halt_at_s_(halt_at_s), halt_duration_s_(halt_duration_s) {
  if (!motion_) throw std::invalid_argument("halt: no motion to halt");
  if (!(std::isfinite(halt_at_s) && halt_at_s >= 0.0)) {
    throw std::invalid_argument("halt.at_s: expected a non-negative time");
  }
  if (!(std::isfinite(halt_duration_s) && halt_duration_s > 0.0)) {
    throw std::invalid_argument("halt.duration_s: expected a positive duration");
  }
}

ReferencePoint HaltedTrajectory::sample(double time_s) const {
  if (time_s < halt_at_s_) return motion_->sample(time_s);
  if (time_s < halt_at_s_ + halt_duration_s_) {
    ReferencePoint stopped;  // at rest where the motion was when it halted
    stopped.position = motion_->sample(halt_at_s_).position;
    return stopped;
  }
  return motion_->sample(time_s - halt_duration_s_);
}

double HaltedTrajectory::duration_s() const {
  const double inner = motion_->duration_s();
  return halt_at_s_ < inner ? inner + halt_duration_s_ : inner;
}

std::vector<double> HaltedTrajectory::corner_times_s() const {
  std::vector<double> corners = motion_->corner_times_s();
  for (double& t : corners) {
    if (t >= halt_at_s_) t += halt_duration_s_;  // the motion reaches it later
  }
  return corners;
}

std::unique_ptr<ReferenceTrajectory> HaltedTrajectory::clone() const {
  return std::make_unique<HaltedTrajectory>(*this);
}

std::string HaltedTrajectory::describe() const {
  std::ostringstream out;
  out << motion_->describe() << ", halted " << halt_duration_s_ * 1e3 << " ms at " << halt_at_s_ << " s";
  return out.str();
}

}  // namespace netmc::control
