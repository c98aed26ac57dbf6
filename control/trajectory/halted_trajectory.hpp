#pragma once
// A desired motion that stops dead for a while and then goes on where it stopped: the reference
// time freezes for `halt_duration_s` at `halt_at_s` and continues shifted by it afterwards
// (thesis, paper 000, case D of Table 2-2: the machine is commanded to halt for 4 ms at
// t = 6 pi s; how it halts is netmc's assumption [A]). The contour is the wrapped motion's: only the timing changes,
// so the desired velocity jumps to zero and back, and the tangential error grows to
// v * halt_duration_s within the halt.

#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

class HaltedTrajectory final : public ReferenceTrajectory {
 public:
  // Throws std::invalid_argument unless 0 <= halt_at_s and 0 < halt_duration_s (both finite).
  HaltedTrajectory(std::shared_ptr<const ReferenceTrajectory> motion, double halt_at_s,
                   double halt_duration_s);

  ReferencePoint sample(double time_s) const override;
  double duration_s() const override;
  double period_s() const override { return motion_->period_s(); }
  double contour_error(const Eigen::Vector2d& point) const override {
    return motion_->contour_error(point);
  }
  const ReferenceTrajectory& geometry() const override { return motion_->geometry(); }
  std::vector<double> corner_times_s() const override;
  std::unique_ptr<ReferenceTrajectory> clone() const override;
  std::string describe() const override;

 private:
  std::shared_ptr<const ReferenceTrajectory> motion_;
  double halt_at_s_, halt_duration_s_;
};

}  // namespace netmc::control
