#include "control/delay_compensation/axis_state_predictor.hpp"

#include <algorithm>
#include <cmath>

#include "control/parameter_check.hpp"

namespace netmc::control {
namespace {

PredictedState advanced(const PredictionModel& model, PredictedState state, double duration_s) {
  advance_model(model, state, duration_s, 0.0);
  return state;
}

Eigen::Vector3d as_vector(const PredictedState& s) {
  return {s.position_m, s.velocity_m_s, s.disturbance_m_s2};
}

}  // namespace

AxisStatePredictor::AxisStatePredictor(const PredictionModel& model, double sample_period_s, double command_limit)
    : model_(model), command_limit_(command_limit) {
  const double h = require_positive(sample_period_s, "sample period");
  require_finite(model.damping_per_s, "prediction model damping");
  require_finite(model.input_gain, "prediction model input gain");
  require_positive(model.observer_bandwidth_rad_s, "prediction model observer bandwidth");
  if (!(command_limit > 0.0)) throw std::invalid_argument("prediction model command limit: expected > 0");
  // The observer corrects after each period's prediction (current-estimator form): its error runs
  // as e(k+1) = (Phi - L C Phi) e(k). L places the three poles at exp(-w h) (Ackermann's formula
  // for the pair (Phi, C Phi)).
  // The gains come from the linear part (friction's slope left out).
  require_non_negative(model.coulomb_m_s2, "prediction model Coulomb friction");
  require_positive(model.coulomb_velocity_scale_m_s, "prediction model friction velocity scale");
  PredictionModel linear = model_;
  linear.coulomb_m_s2 = 0.0;
  Eigen::Matrix3d phi;
  phi.col(0) = as_vector(advanced(linear, {1.0, 0.0, 0.0}, h));
  phi.col(1) = as_vector(advanced(linear, {0.0, 1.0, 0.0}, h));
  phi.col(2) = as_vector(advanced(linear, {0.0, 0.0, 1.0}, h));
  const Eigen::RowVector3d c_phi = phi.row(0);
  Eigen::Matrix3d observability;
  observability.row(0) = c_phi;
  observability.row(1) = c_phi * phi;
  observability.row(2) = c_phi * phi * phi;
  const double pole = std::exp(-model_.observer_bandwidth_rad_s * h);
  const Eigen::Matrix3d shifted = phi - pole * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d characteristic = shifted * shifted * shifted;
  correction_gain_ = characteristic * observability.inverse() * Eigen::Vector3d::UnitZ();
  if (!correction_gain_.allFinite()) {
    throw std::invalid_argument("prediction model: the observer cannot be placed (input gain " +
                                std::to_string(model.input_gain) + ", damping " + std::to_string(model.damping_per_s) + ")");
  }
  pending_.reserve(64);
  by_arrival_.reserve(64);
}

void AxisStatePredictor::reset(double position_m) {
  estimate_ = {position_m, 0.0, 0.0};
  state_time_s_ = 0.0;
  measured_position_m_ = position_m;
  has_measurement_ = false;
  newest_sample_ = 0;
  input_in_force_ = 0.0;
  input_sequence_ = 0;
  has_input_sequence_ = false;
  pending_.clear();
}

void AxisStatePredictor::command_sent(std::uint64_t sequence, double command, double expected_arrival_s) {
  if (!std::isfinite(expected_arrival_s)) return;  // no instant to act at: not modelled
  const double applied = std::isfinite(command) ? std::clamp(command, -command_limit_, command_limit_) : 0.0;
  if (pending_.size() >= kMaxPendingCommands) {
    input_in_force_ = pending_.front().value;
    input_sequence_ = pending_.front().sequence;
    has_input_sequence_ = true;
    pending_.erase(pending_.begin());
  }
  pending_.push_back({sequence, applied, expected_arrival_s, false});
}

void AxisStatePredictor::command_applied(std::uint64_t sequence, double arrival_s) {
  if (!std::isfinite(arrival_s)) return;  // a report that is no time
  for (auto& command : pending_) {
    if (command.sequence == sequence) {
      command.arrival_s = arrival_s;
      command.reported = true;
      return;
    }
  }
}

void AxisStatePredictor::command_played(std::uint64_t sequence, double arrival_s, double command) {
  if (!std::isfinite(arrival_s) || !std::isfinite(command)) return;  // a report that is no time or no command
  if (has_input_sequence_ && sequence <= input_sequence_) return;     // settled already
  const double applied = std::clamp(command, -command_limit_, command_limit_);
  const auto at = std::lower_bound(pending_.begin(), pending_.end(), sequence,
                                   [](const Command& c, std::uint64_t s) { return c.sequence < s; });
  if (at != pending_.end() && at->sequence == sequence) {
    *at = {sequence, applied, arrival_s, true};
    return;
  }
  if (pending_.size() >= kMaxPendingCommands) return;  // bounded whatever the reports say
  pending_.insert(at, {sequence, applied, arrival_s, true});
}

void AxisStatePredictor::settle_commands_until(double time_s) {
  for (const auto& command : pending_) {
    // The axis keeps the newest sequence that has arrived: a late older one is dropped.
    if (command.reported && command.arrival_s <= time_s &&
        (!has_input_sequence_ || command.sequence > input_sequence_)) {
      input_in_force_ = command.value;
      input_sequence_ = command.sequence;
      has_input_sequence_ = true;
    }
  }
  if (has_input_sequence_) {
    std::erase_if(pending_, [&](const Command& c) { return c.sequence <= input_sequence_; });
  }
}

void AxisStatePredictor::advance(PredictedState& state, double from_s, double to_s, double known_s) const {
  by_arrival_.clear();
  for (const auto& command : pending_) {
    if (counts(command, known_s)) by_arrival_.push_back(&command);
  }
  std::stable_sort(by_arrival_.begin(), by_arrival_.end(),
                   [](const Command* a, const Command* b) { return a->arrival_s < b->arrival_s; });
  double input = input_in_force_;
  std::uint64_t sequence = input_sequence_;
  bool has_sequence = has_input_sequence_;
  double time = from_s;
  for (const Command* command : by_arrival_) {
    if (command->arrival_s >= to_s) break;
    if (has_sequence && command->sequence <= sequence) continue;  // stale at the axis
    if (command->arrival_s > time) {
      advance_model(model_, state, command->arrival_s - time, input);
      time = command->arrival_s;
    }
    input = command->value;
    sequence = command->sequence;
    has_sequence = true;
  }
  if (to_s > time) advance_model(model_, state, to_s - time, input);
}

void AxisStatePredictor::measured(std::uint64_t sequence, double sample_time_s, double position_m) {
  if (!std::isfinite(position_m) || !std::isfinite(sample_time_s)) return;
  if (has_measurement_ && sequence <= newest_sample_) return;
  if (has_measurement_ || sample_time_s > state_time_s_) {
    // Run the observer from its last sample to this one, then correct with the innovation.
    advance(estimate_, state_time_s_, sample_time_s, sample_time_s);
    state_time_s_ = std::max(state_time_s_, sample_time_s);
    settle_commands_until(state_time_s_);
  }
  const double innovation = position_m - estimate_.position_m;
  estimate_.position_m += correction_gain_[0] * innovation;
  estimate_.velocity_m_s += correction_gain_[1] * innovation;
  estimate_.disturbance_m_s2 += correction_gain_[2] * innovation;
  measured_position_m_ = position_m;
  newest_sample_ = sequence;
  has_measurement_ = true;
}

PredictedState AxisStatePredictor::estimate() const {
  PredictedState out = estimate_;
  out.position_m = measured_position_m_;
  return out;
}

double AxisStatePredictor::predict_position(double time_s) const { return predict_state(time_s).position_m; }

PredictedState AxisStatePredictor::predict_state(double time_s) const {
  PredictedState state = estimate();
  if (!(time_s > state_time_s_)) return state;
  advance(state, state_time_s_, time_s, state_time_s_);
  return state;
}

PredictedState AxisStatePredictor::run_on(PredictedState state, double duration_s, double command) const {
  const double applied = std::isfinite(command) ? std::clamp(command, -command_limit_, command_limit_) : 0.0;
  if (duration_s > 0.0) advance_model(model_, state, duration_s, applied);
  return state;
}

}  // namespace netmc::control
