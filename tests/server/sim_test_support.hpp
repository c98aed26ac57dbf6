#pragma once
// Small jobs for the runner tests: paper 001's circle on a friction-free linear axis pair, and
// the thesis's ellipse on the linear motors.

#include <memory>
#include <numbers>

#include "control/trajectory/circle_trajectory.hpp"
#include "control/trajectory/ellipse_trajectory.hpp"
#include "plant/plant_catalog.hpp"
#include "plant/second_order_axis.hpp"
#include "server/job/controller_registry.hpp"
#include "server/sim/contour_job.hpp"

namespace netmc::sim::testing {

// The job's controller `name` as netmc builds it (the registry), with `spec`'s gains. Call again
// after changing the job's reference or axes: the controller is built for them.
inline void use_controller(ContourJob& job, const std::string& name, netmc::v1::ControllerSpec spec = {}) {
  spec.set_name(name);
  job.controller_name = name;
  job.controller_factory = job::ControllerRegistry::global().resolve(spec, job.reference, job.axis_names,
                                                                     job.sample_period_s);
}

// The planar trajectory of a two-axis job.
inline const control::ReferenceTrajectory& planar_trajectory(const ContourJob& job) {
  return *std::get<std::shared_ptr<const control::ReferenceTrajectory>>(job.reference);
}

inline ContourJob small_circle_job(const std::string& controller = "adrc") {
  ContourJob job;
  job.reference = std::make_shared<control::CircleTrajectory>(control::CircleParameters{{0.05, 0.05}, 0.01, 2.0});
  job.axis_names = {"x", "y"};
  plant::SecondOrderAxisParameters axis;
  axis.a1 = 0.0;
  axis.a2 = -20.0;
  axis.b = 20.0;
  job.axes = {std::make_shared<plant::SecondOrderAxis>(axis),
              std::make_shared<plant::SecondOrderAxis>(axis)};
  job.plant_name = "linear";
  job.sample_period_s = 0.005;
  job.iterations = 1;
  job.seed = 7;
  use_controller(job, controller);
  return job;
}

// Thesis (paper 000) eq. 2-68: x = 0.2 sin 7t, y = 0.02 - 0.02 cos 7t (1.4 m/s, 9.8 m/s^2), on
// the linear-motor plant, h = 0.2 ms, 0.5 um encoder.
inline ContourJob thesis_ellipse_job(const std::string& controller, double revolutions) {
  ContourJob job;
  control::EllipseParameters ellipse;
  ellipse.center = {0.0, 0.02};
  ellipse.semi_axis_x_m = 0.2;
  ellipse.semi_axis_y_m = 0.02;
  ellipse.period_s = 2.0 * std::numbers::pi / 7.0;
  ellipse.start_angle_rad = -std::numbers::pi / 2.0;
  ellipse.revolutions = revolutions;
  job.reference = std::make_shared<control::EllipseTrajectory>(ellipse);
  job.axis_names = {"x", "y"};
  auto plants = plant::make_plant_set("linmotor", 2);
  for (auto& axis : plants.axes) job.axes.emplace_back(std::move(axis));
  job.plant_name = "linmotor";
  job.sample_period_s = 2e-4;
  job.sensor.resolution_m = 0.5e-6;
  use_controller(job, controller);
  return job;
}

}  // namespace netmc::sim::testing
