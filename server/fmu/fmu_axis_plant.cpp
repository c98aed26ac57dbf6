#include "server/fmu/fmu_axis_plant.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "plant/parameter_checks.hpp"
#include "server/fmu/printable_text.hpp"

namespace netmc::plant::fmu {
namespace {

constexpr const char* kOwner = "FmuAxisPlant";

// Equal up to the round-off of a start value written in decimal and read back.
bool same_value(double a, double b) {
  return std::abs(a - b) <= 1e-12 * std::max({1.0, std::abs(a), std::abs(b)});
}

}  // namespace

FmuAxisPlant::FmuAxisPlant(std::shared_ptr<const FmuAxisSetup> setup, Unprobed) : setup_(std::move(setup)) {}

FmuAxisPlant::FmuAxisPlant(std::shared_ptr<const FmuAxisSetup> setup) : FmuAxisPlant(std::move(setup), Unprobed{}) {
  initialise(std::nullopt);
  default_position_ = position_;
  default_velocity_ = velocity_;
  instance_.reset();  // lazy from here: see the header
}

FmuAxisPlant::~FmuAxisPlant() = default;

std::string FmuAxisPlant::name() const {
  return "fmu " + printable_text(setup_->model->path()) + " (axis " + std::to_string(setup_->axis) + ")";
}

void FmuAxisPlant::fail(const std::string& why) const { throw std::runtime_error(name() + ": " + why); }

void FmuAxisPlant::initialise(const std::optional<Start>& start) {
  const FmuAxisSetup& s = *setup_;
  // FMI 2.0, 2.1.6: fmi2Reset returns an instance to its state after fmi2Instantiate.
  if (instance_ == nullptr || !instance_->reset()) {
    instance_.reset();  // freed before its successor exists (once-per-process models)
    instance_ = std::make_unique<FmuInstance>(s.model, "netmc-axis" + std::to_string(s.axis));
  }
  // FMI 2.0, 2.1.6 / 4.2.4: in the Instantiated state, fmi2SetupExperiment, then the start
  // values of parameters and states (fmi2SetReal), then the initialisation mode.
  instance_->setup_experiment(0.0);
  for (const auto& [variable, value] : s.parameters) instance_->set_real(variable, value, 0.0);
  if (start && s.position_start) instance_->set_real(*s.position_start, start->position, 0.0);
  if (start && s.velocity_start) instance_->set_real(*s.velocity_start, start->velocity, 0.0);
  instance_->enter_initialization_mode();
  instance_->exit_initialization_mode();
  time_ = 0.0;
  position_ = instance_->get_real(s.output, 0.0);
  if (s.velocity) {
    velocity_ = instance_->get_real(*s.velocity, 0.0);
  } else if (s.velocity_start) {
    velocity_ = instance_->get_real(*s.velocity_start, 0.0);  // parameters stay readable
  } else {
    velocity_ = 0.0;
  }
  if (!std::isfinite(position_) || !std::isfinite(velocity_)) {
    std::ostringstream out;
    out << "the initial position or velocity is not finite (" << position_ << " m, " << velocity_ << " m/s)";
    fail(out.str());
  }
}

void FmuAxisPlant::reset(double position, double velocity) {
  require_finite(kOwner, "position", position);
  require_finite(kOwner, "velocity", velocity);
  const FmuAxisSetup& s = *setup_;
  if (!s.position_start && !same_value(position, default_position_)) {
    std::ostringstream out;
    out.precision(12);
    out << name() << ": cannot reset to x = " << position << " m: no variable takes the start position "
        << "(the FMU has no x0; name one with position_start=NAME), and the FMU starts at " << default_position_
        << " m";
    throw std::invalid_argument(out.str());
  }
  if (!s.velocity_start && !same_value(velocity, default_velocity_)) {
    std::ostringstream out;
    out.precision(12);
    out << name() << ": cannot reset to v = " << velocity << " m/s: no variable takes the start velocity "
        << "(the FMU has no v0; name one with velocity_start=NAME), and the FMU starts at " << default_velocity_
        << " m/s";
    throw std::invalid_argument(out.str());
  }
  broken_ = true;  // until the new start is reached
  history_.clear();
  history_overflowed_ = false;
  start_ = Start{position, velocity};
  initialise(start_);
  broken_ = false;
}

void FmuAxisPlant::read_outputs(double previous_position, double step_s) {
  const FmuAxisSetup& s = *setup_;
  position_ = instance_->get_real(s.output, time_);
  velocity_ = s.velocity ? instance_->get_real(*s.velocity, time_) : (position_ - previous_position) / step_s;
  if (!std::isfinite(position_) || !std::isfinite(velocity_)) {
    std::ostringstream out;
    out.precision(12);
    out << "output " << quoted(s.velocity && std::isfinite(position_) ? s.velocity->name : s.output.name)
        << " is not finite (" << (std::isfinite(position_) ? velocity_ : position_) << ") at t = " << time_ << " s";
    fail(out.str());
  }
}

void FmuAxisPlant::advance(double duration_s, double input) {
  require_advance_arguments(kOwner, duration_s, input);
  if (duration_s == 0.0) return;
  if (broken_) fail("an earlier FMU call failed or a reset() did not complete; reset() the plant first");
  const FmuAxisSetup& s = *setup_;
  long long steps = 0;
  double step = 0.0;
  if (s.fixed_step) {
    // FMI 2.0, 4.3.1: canHandleVariableCommunicationStepSize = false: every step is `step`.
    const double count = std::round(duration_s / s.step_s);
    if (!(count >= 1.0) || std::abs(count * s.step_s - duration_s) > 1e-9 * duration_s || count > 1e12) {
      std::ostringstream out;
      out.precision(12);
      out << "advance(" << duration_s << " s) is not a whole number of the FMU's fixed communication step "
          << s.step_s << " s (the FMU cannot vary its step: canHandleVariableCommunicationStepSize is false)";
      throw std::runtime_error(name() + ": " + out.str());
    }
    steps = static_cast<long long>(count);
    step = s.step_s;
  } else {
    steps = substep_count(kOwner, duration_s, s.step_s);
    step = duration_s / static_cast<double>(steps);
  }
  try {
    if (instance_ == nullptr) {
      broken_ = true;
      initialise(start_);
      broken_ = false;
    }
    broken_ = true;  // until the advance is complete
    instance_->set_real(s.input, input, time_);
    for (long long i = 0; i < steps; ++i) {
      const double before = position_;
      instance_->do_step(time_, step);
      time_ += step;
      read_outputs(before, step);
    }
    broken_ = false;
  } catch (...) {
    history_.clear();
    throw;
  }
  if (history_overflowed_) return;
  if (history_.size() == kMaxReplayedAdvances) {
    history_overflowed_ = true;
    std::vector<Advance>().swap(history_);
    return;
  }
  history_.push_back({duration_s, input});
}

std::unique_ptr<AxisPlant> FmuAxisPlant::clone() const {
  std::unique_ptr<FmuAxisPlant> copy(new FmuAxisPlant(setup_, Unprobed{}));
  copy->default_position_ = default_position_;
  copy->default_velocity_ = default_velocity_;
  copy->start_ = start_;
  if (instance_ == nullptr && !broken_) {
    // Never instantiated (or freed right after the probe): the clone starts where this one is.
    copy->position_ = position_;
    copy->velocity_ = velocity_;
    copy->time_ = time_;
    return copy;
  }
  if (broken_) fail("cannot clone a plant whose last FMU call failed; reset() it first");
  if (history_overflowed_) {
    fail("cannot clone a plant advanced more than " + std::to_string(kMaxReplayedAdvances) +
         " times since its reset(): a clone replays them (see fmu_axis_plant.hpp)");
  }
  copy->initialise(start_);
  for (const Advance& a : history_) copy->advance(a.duration_s, a.input);
  return copy;
}

std::string FmuAxisPlant::describe() const {
  const FmuAxisSetup& s = *setup_;
  std::ostringstream out;
  out << "fmu:" << printable_text(s.options_text) << " (model " << quoted(s.model->description().model_name)
      << ", FMI " << printable_text(s.model->description().fmi_version) << " co-simulation), axis " << s.axis
      << ": input " << s.input.name << ", output " << s.output.name << ", velocity "
      << (s.velocity ? s.velocity->name : "estimated from the position") << ", step " << s.step_s << " s"
      << (s.fixed_step ? " (fixed)" : "") << ", position_start " << (s.position_start ? s.position_start->name : "none")
      << ", velocity_start " << (s.velocity_start ? s.velocity_start->name : "none");
  if (!s.parameters.empty()) {
    out << ", parameters";
    const char* separator = " ";
    for (const auto& [variable, value] : s.parameters) {
      out << separator << variable.name << "=" << value;
      separator = ", ";
    }
  }
  return out.str();
}

}  // namespace netmc::plant::fmu
