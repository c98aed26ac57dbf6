#include "control/axis/feedforward_pid_axis.hpp"

#include <sstream>
#include <stdexcept>

#include "control/frequency/qft_bounds.hpp"
#include "control/parameter_check.hpp"

namespace netmc::control {
namespace {

const FeedforwardPidGains& checked(const FeedforwardPidGains& gains, double sample_period_s) {
  require_positive(gains.mass_kg, "ffpid mass_kg");
  require_positive(gains.bandwidth_hz, "ffpid bandwidth_hz");
  require_positive(gains.alpha, "ffpid alpha");
  require_positive(gains.low_pass_damping, "ffpid low_pass_damping");
  require_finite(gains.feedforward_fraction, "ffpid feedforward_fraction");
  require_positive(sample_period_s, "sample period");
  const double low_pass_hz = gains.alpha * gains.bandwidth_hz;
  const double nyquist_hz = 0.5 / sample_period_s;
  if (!(low_pass_hz < nyquist_hz)) {
    std::ostringstream text;
    text << "ffpid alpha * bandwidth_hz: the low-pass corner " << low_pass_hz
         << " Hz must lie below the Nyquist frequency " << nyquist_hz << " Hz";
    throw std::invalid_argument(text.str());
  }
  return gains;
}

}  // namespace

namespace {

FeedforwardPidGains gains_of(const StageAxisModel& axis) {
  FeedforwardPidGains gains;
  gains.mass_kg = axis.mass_kg;
  gains.bandwidth_hz = axis.bandwidth_hz;
  gains.alpha = axis.alpha;
  return gains;
}

}  // namespace

FeedforwardPidGains paper004_x_axis_gains() { return gains_of(paper004_x_axis()); }
FeedforwardPidGains paper004_y_axis_gains() { return gains_of(paper004_y_axis()); }

TransferFunction feedforward_pid_feedback(const FeedforwardPidGains& gains) {
  // paper 004, eq. 2: the resonances of the plant do not enter G_c.
  StageAxisModel axis;
  axis.mass_kg = gains.mass_kg;
  axis.bandwidth_hz = gains.bandwidth_hz;
  axis.alpha = gains.alpha;
  return stage_axis_feedback(axis, gains.low_pass_damping);
}

FeedforwardPidAxis::FeedforwardPidAxis(const FeedforwardPidGains& gains, double sample_period_s)
    : gains_(checked(gains, sample_period_s)),
      continuous_(feedforward_pid_feedback(gains_)),
      discrete_(tustin(continuous_, sample_period_s)),
      feedback_(discrete_) {}

void FeedforwardPidAxis::reset() { feedback_.reset(); }

double FeedforwardPidAxis::step(double reference_position, double reference_acceleration,
                                double measured_position) {
  return feedback_.step(reference_position - measured_position) + feedforward(reference_acceleration);
}

std::string FeedforwardPidAxis::describe() const {
  std::ostringstream text;
  text << "ffpid(m=" << gains_.mass_kg << " kg, f_bw=" << gains_.bandwidth_hz << " Hz, alpha=" << gains_.alpha
       << ", ff=" << gains_.feedforward_fraction << ")";
  return text.str();
}

}  // namespace netmc::control
