#include "control/data_driven/data_driven_contouring.hpp"

#include <sstream>
#include <stdexcept>

#include "control/parameter_check.hpp"

namespace netmc::control {

Eigen::Vector2d coupled_increments(const AxisPrediction& x, const AxisPrediction& y, const Eigen::Vector2d& normal) {
  if (x.rule != y.rule) throw std::logic_error("data-driven contouring: both axes must use the same rule");
  const Eigen::Matrix2d weight = Eigen::Vector2d(x.contour_weight, y.contour_weight).asDiagonal();
  const Eigen::Matrix2d projection = normal * normal.transpose();
  const Eigen::Matrix2d m = Eigen::Matrix2d::Identity() + weight * projection;
  const Eigen::Vector2d tracking(x.tracking_error, y.tracking_error);
  const Eigen::Vector2d offset =
      weight * (Eigen::Vector2d(x.contour_error, y.contour_error) - projection * tracking);
  const Eigen::Vector2d free(x.free_error, y.free_error);
  const Eigen::Vector2d gain(x.gain, y.gain);
  if (x.rule == IncrementRule::least_squares) {
    // min |m (free + diag(gain) du) + offset|^2 + du^T diag(lambda) du, then the step rho.
    const Eigen::Matrix2d g = m * gain.asDiagonal();
    Eigen::Matrix2d h = g.transpose() * g;
    h(0, 0) += x.lambda;
    h(1, 1) += y.lambda;
    const Eigen::Vector2d step = h.inverse() * (g.transpose() * (m * free + offset));
    return -Eigen::Vector2d(x.rho * step[0], y.rho * step[1]);
  }
  // m e_tr(k+1) + offset = target (eq. 24 with the coupled eps(k+1), eq. 25's term in target).
  const Eigen::Vector2d wanted = m.inverse() * (Eigen::Vector2d(x.target, y.target) - offset);
  return (wanted - free).cwiseQuotient(gain);
}

DataDrivenContouring::DataDrivenContouring(std::unique_ptr<DataDrivenAxisLaw> x_axis,
                                           std::unique_ptr<DataDrivenAxisLaw> y_axis,
                                           std::unique_ptr<ContourErrorEstimator> estimator,
                                           double sample_period_s, double length_unit_m,
                                           ContourCoupling coupling)
    : axes_{std::move(x_axis), std::move(y_axis)},
      estimator_(std::move(estimator)),
      h_(require_positive(sample_period_s, "sample period")),
      scale_(1.0 / require_positive(length_unit_m, "data-driven length unit")),
      coupling_(coupling) {
  if (!axes_[0] || !axes_[1] || !estimator_) {
    throw std::invalid_argument("data-driven contouring: every part must be given");
  }
}

DataDrivenContouring::DataDrivenContouring(const DataDrivenContouring& other)
    : axes_{other.axes_[0]->clone(), other.axes_[1]->clone()},
      estimator_(other.estimator_->clone()),
      h_(other.h_),
      scale_(other.scale_),
      coupling_(other.coupling_) {}

void DataDrivenContouring::begin_iteration(const Eigen::Vector2d& initial_position, std::size_t) {
  for (int axis = 0; axis < 2; ++axis) axes_[axis]->reset(scale_ * initial_position[axis]);
}

ContouringCycle DataDrivenContouring::step(std::size_t, const ReferencePoint& reference,
                                           const Eigen::Vector2d& measured) {
  ContouringCycle out;
  out.estimate = estimator_->estimate(reference, measured);
  const Eigen::Vector2d error_vector = contour_error_vector(out.estimate);
  // y_d(k+1), y_d(k+2) from the reference's own derivatives (third-order error, ~1e-9 of a step here).
  const Eigen::Vector2d next = reference.position + h_ * reference.velocity + 0.5 * h_ * h_ * reference.acceleration;
  const Eigen::Vector2d after = reference.position + 2.0 * h_ * reference.velocity + 2.0 * h_ * h_ * reference.acceleration;
  AxisPrediction prediction[2];
  for (int axis = 0; axis < 2; ++axis) {
    prediction[axis] = axes_[axis]->predict(scale_ * measured[axis], scale_ * reference.position[axis],
                                            scale_ * next[axis], scale_ * after[axis], scale_ * error_vector[axis]);
  }
  // The unit normal of the estimate (eps along (cx, -cy)); none at a degenerate estimate.
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();
  const Eigen::Vector2d direction(out.estimate.cx, -out.estimate.cy);
  if (coupling_ == ContourCoupling::through_outputs && direction.norm() > 0.0) normal = direction.normalized();
  const Eigen::Vector2d increment = coupled_increments(prediction[0], prediction[1], normal);
  for (int axis = 0; axis < 2; ++axis) out.axis_command[axis] = axes_[axis]->commit(increment[axis]);
  out.command = out.axis_command;
  return out;
}

std::string DataDrivenContouring::describe() const {
  std::ostringstream out;
  out << axes_[0]->describe() << " x " << axes_[1]->describe() << " [estimator " << estimator_->name()
      << ", unit " << 1.0 / scale_ << " m, coupling "
      << (coupling_ == ContourCoupling::through_outputs ? "eps(k+1) through y(k+1)" : "eps(k+1) = eps(k)") << "]";
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
