#include "control/data_driven/data_driven_contouring.hpp"

#include <sstream>
#include <stdexcept>

#include "control/parameter_check.hpp"

namespace netmc::control {

DataDrivenContouring::DataDrivenContouring(std::unique_ptr<DataDrivenAxisLaw> x_axis,
                                           std::unique_ptr<DataDrivenAxisLaw> y_axis,
                                           std::unique_ptr<ContourErrorEstimator> estimator,
                                           double sample_period_s, double length_unit_m)
    : axes_{std::move(x_axis), std::move(y_axis)},
      estimator_(std::move(estimator)),
      h_(require_positive(sample_period_s, "sample period")),
      scale_(1.0 / require_positive(length_unit_m, "data-driven length unit")) {
  if (!axes_[0] || !axes_[1] || !estimator_) {
    throw std::invalid_argument("data-driven contouring: every part must be given");
  }
}

DataDrivenContouring::DataDrivenContouring(const DataDrivenContouring& other)
    : axes_{other.axes_[0]->clone(), other.axes_[1]->clone()},
      estimator_(other.estimator_->clone()),
      h_(other.h_),
      scale_(other.scale_) {}

void DataDrivenContouring::begin_iteration(const Eigen::Vector2d& initial_position, std::size_t) {
  for (int axis = 0; axis < 2; ++axis) axes_[axis]->reset(scale_ * initial_position[axis]);
}

ContouringCycle DataDrivenContouring::step(std::size_t, const ReferencePoint& reference,
                                           const Eigen::Vector2d& measured) {
  ContouringCycle out;
  out.estimate = estimator_->estimate(reference, measured);
  const Eigen::Vector2d error_vector = contour_error_vector(out.estimate);
  // y_d(k+1) from the reference's own derivatives (third-order error, ~1e-9 of a step here).
  const Eigen::Vector2d next = reference.position + h_ * reference.velocity + 0.5 * h_ * h_ * reference.acceleration;
  for (int axis = 0; axis < 2; ++axis) {
    out.axis_command[axis] = axes_[axis]->command(scale_ * measured[axis], scale_ * reference.position[axis],
                                                  scale_ * next[axis], scale_ * error_vector[axis]);
  }
  out.command = out.axis_command;
  return out;
}

std::string DataDrivenContouring::describe() const {
  std::ostringstream out;
  out << axes_[0]->describe() << " x " << axes_[1]->describe() << " [estimator " << estimator_->name()
      << ", unit " << 1.0 / scale_ << " m]";
  return out.str();
}

std::vector<EstimateName> DataDrivenContouring::estimate_names() const {
  std::vector<EstimateName> names;
  for (int axis = 0; axis < 2; ++axis) {
    for (std::size_t i = 0; i < axes_[axis]->estimate_count(); ++i) {
      const NamedEstimate e = axes_[axis]->estimate(i);
      names.push_back({std::string(axis == 0 ? "x_" : "y_") + e.name, e.unit});
    }
  }
  return names;
}

void DataDrivenContouring::read_estimates(double* out) const {
  for (int axis = 0; axis < 2; ++axis) {
    for (std::size_t i = 0; i < axes_[axis]->estimate_count(); ++i) *out++ = axes_[axis]->estimate(i).value;
  }
}

}  // namespace netmc::control
