#pragma once
// One axis of a data-driven contouring controller (paper 002). Each sample is split in two so that
// the composition (DataDrivenContouring) can choose both axes' increments jointly:
//   predict(): from the measured position, the desired positions at k, k+1, k+2 and this axis's
//              component of the estimated contour-error vector (all in the controller's length
//              unit), update the data model and return what du(k) will do: the free response's
//              tracking error at the sample du(k) first moves, the gain of du(k) on it, and the
//              law's rule (C3's least-squares step or C4's reaching-law target);
//   commit():  take du(k) and return u(k) = u(k-1) + du(k).
// command() is the per-axis law with eps(k+1) ~ eps(k) (netmc's first reading of eq. 24 [A]), i.e. the
// composition's coupling with no normal (data_driven_contouring.hpp).

#include <memory>
#include <string>

namespace netmc::control {

struct NamedEstimate {
  const char* name;  // e.g. "phi_hat"
  const char* unit;  // e.g. "um/V"
  double value;
};

// How a law turns its prediction into du(k).
enum class IncrementRule {
  // C3: du = -rho G E / (lambda + G^2) for the predicted composite error E (MFAC's one-step
  // penalised least squares, jointly over both axes in the composition).
  least_squares,
  // C4: du such that the composite error at the target sample equals `target` (eq. 24 + 25).
  reaching_target,
};

struct AxisPrediction {
  IncrementRule rule = IncrementRule::least_squares;
  double free_error = 0.0;      // y^(k+1+d | du(k) = 0) - y_d(k+1+d), d = 0 compact, 1 full
  double gain = 1.0;            // d y(k+1+d) / d du(k) (Phi^ or b0^)
  double tracking_error = 0.0;  // y(k) - y_d(k)
  double contour_error = 0.0;   // this axis's eps(k)
  double contour_weight = 0.0;  // delta of eq. 16
  double rho = 1.0, lambda = 0.0;  // least_squares: step and penalty
  double target = 0.0;          // reaching_target: composite error wanted at k+1+d, switching included
};

class DataDrivenAxisLaw {
 public:
  virtual ~DataDrivenAxisLaw() = default;
  virtual void reset(double position) = 0;
  virtual AxisPrediction predict(double position, double desired, double desired_next, double desired_after,
                                 double contour_error) = 0;
  virtual double commit(double increment) = 0;
  virtual std::unique_ptr<DataDrivenAxisLaw> clone() const = 0;
  virtual std::string describe() const = 0;
  // The law's internal estimates after the last command (Phi^, Psi^, d^, s ...).
  virtual std::size_t estimate_count() const = 0;
  virtual NamedEstimate estimate(std::size_t index) const = 0;

  // Per axis, eps(k+1+d) ~ eps(k): the composite error is e_tr + delta eps(k).
  double command(double position, double desired, double desired_next, double desired_after, double contour_error) {
    return commit(uncoupled_increment(predict(position, desired, desired_next, desired_after, contour_error)));
  }

  static double uncoupled_increment(const AxisPrediction& p) {
    const double offset = p.contour_weight * p.contour_error;
    if (p.rule == IncrementRule::least_squares) {
      return -p.rho * p.gain * (p.free_error + offset) / (p.lambda + p.gain * p.gain);
    }
    return (p.target - offset - p.free_error) / p.gain;
  }
};

}  // namespace netmc::control
