#include "control/task_space/trajectory_initialization_filter.hpp"

#include <cmath>

#include "control/parameter_check.hpp"

namespace netmc::control {

TrajectoryInitializationFilter::TrajectoryInitializationFilter(double contour_bandwidth,
                                                               double tangential_bandwidth)
    : bandwidth_(require_positive(contour_bandwidth, "initialization filter wc"),
                 require_positive(tangential_bandwidth, "initialization filter wm")) {}

void TrajectoryInitializationFilter::start(const Eigen::Vector2d& initial_offset,
                                           const Eigen::Vector2d& initial_offset_rate) {
  initial_ = initial_offset;
  initial_rate_ = initial_offset_rate;
}

FilterOffset TrajectoryInitializationFilter::offset(double t) const {
  // Critically damped: z = (a + b t) e^(-w t), a = z0, b = z0' + w z0.
  FilterOffset out;
  for (int i = 0; i < 2; ++i) {
    const double w = bandwidth_[i];
    const double a = initial_[i];
    const double b = initial_rate_[i] + w * a;
    const double decay = std::exp(-w * t);
    out.value[i] = (a + b * t) * decay;
    out.rate[i] = (b - w * (a + b * t)) * decay;
    out.acceleration[i] = (-2.0 * w * b + w * w * (a + b * t)) * decay;
  }
  return out;
}

}  // namespace netmc::control
