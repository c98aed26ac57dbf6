#pragma once
// Paper 002's heart-shaped contour with two sharp corners (cusps, where the desired velocity
// vanishes): x = cx + 16 s sin^3(phi), y = cy + s (13 cos phi - 5 cos 2phi - 2 cos 3phi - cos 4phi),
// phi = 2 pi t / period (paper 002 gives neither equation nor size: netmc's assumption [A],
// s = 2.5 mm, centre (75, 75) mm, period 10 s).

#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

struct HeartParameters {
  Eigen::Vector2d center = Eigen::Vector2d(0.075, 0.075);
  double scale_m = 0.0025;
  double period_s = 10.0;
};

class HeartTrajectory final : public ReferenceTrajectory {
 public:
  explicit HeartTrajectory(const HeartParameters& parameters);

  ReferencePoint sample(double time_s) const override;
  double duration_s() const override;
  // Exact distance by global search (no closed form); positive outside the heart.
  double contour_error(const Eigen::Vector2d& point) const override;
  // The two cusps: the top (phi = 0, also the end) and the bottom tip (phi = pi).
  std::vector<double> corner_times_s() const override { return {0.0, 0.5 * p_.period_s}; }
  std::unique_ptr<ReferenceTrajectory> clone() const override;
  std::string describe() const override;

 private:
  HeartParameters p_;
  double rate_;  // d phi / dt
};

}  // namespace netmc::control
