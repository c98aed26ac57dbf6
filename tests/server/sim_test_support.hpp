#pragma once
// Small jobs for the runner tests: paper 001's circle on a friction-free linear axis pair.

#include <memory>

#include "control/circle_trajectory.hpp"
#include "plant/second_order_axis.hpp"
#include "server/sim/contour_job.hpp"

namespace netmc::sim::testing {

inline ContourJob small_circle_job(const std::string& controller = "adrc") {
  ContourJob job;
  job.trajectory = std::make_shared<control::CircleTrajectory>(
      control::CircleParameters{{0.05, 0.05}, 0.01, 2.0});
  plant::SecondOrderAxisParameters axis;
  axis.a1 = 0.0;
  axis.a2 = -20.0;
  axis.b = 20.0;
  job.axes = {std::make_shared<plant::SecondOrderAxis>(axis),
              std::make_shared<plant::SecondOrderAxis>(axis)};
  job.plant_name = "linear";
  job.controller_name = controller;
  job.sample_period_s = 0.005;
  job.iterations = 1;
  job.seed = 7;
  return job;
}

}  // namespace netmc::sim::testing
