#pragma once
// Linear tracking differentiator of ADRC: a critically damped second-order filter that turns a
// (possibly non-smooth) position reference into a smooth position v1 and velocity v2.

namespace netmc::control {

class TrackingDifferentiator {
 public:
  // speed_factor r0 [1/s]: both poles at -r0; sample period h [s].
  TrackingDifferentiator(double speed_factor, double sample_period_s);

  void reset(double position, double velocity = 0.0);
  // Forward-Euler step with the reference sample v0(k) (paper 001, eq. 8).
  void update(double reference);

  double position() const { return v1_; }
  double velocity() const { return v2_; }

 private:
  double r0_;
  double h_;
  double v1_ = 0.0;
  double v2_ = 0.0;
};

}  // namespace netmc::control
