#pragma once
// State prediction over a measured network delay for one axis (the Smith predictor's idea for
// time-stamped samples: Yi, An and Choi's step-ahead predictor; the filtered Smith predictor for
// stochastic delays). Two time lines meet here:
// - the sample's: an observer of position, velocity and lumped disturbance runs at the instants
//   the axis sampled, driven by the commands that were in force at the axis then (each command
//   acts from its arrival, older ones arriving later are dropped as the axis drops them);
// - the actuation's: from the newest sample, the model is run forward with the commands already
//   sent, to the instant the next command will act.
// The prediction starts from the measured position itself, so a zero horizon returns the
// measurement unchanged (no harm without delay); only velocity and disturbance come from the
// observer.

#include <Eigen/Dense>
#include <cstdint>
#include <limits>
#include <vector>

#include "control/delay_compensation/prediction_model.hpp"

namespace netmc::control {

class AxisStatePredictor {
 public:
  // Commands beyond +-command_limit act as the limit (the axis saturates them).
  AxisStatePredictor(const PredictionModel& model, double sample_period_s,
                     double command_limit = std::numeric_limits<double>::infinity());

  // An iteration starts: the axis at rest at `position_m` at t = 0, input 0, nothing in flight.
  void reset(double position_m);
  // Command `sequence` leaves for the axis and is expected to act from `expected_arrival_s`.
  // Sequences increase.
  void command_sent(std::uint64_t sequence, double command, double expected_arrival_s);
  // The axis reports when command `sequence` began to act (the time-stamped loop). A command the
  // axis has not reported by the time of a newer sample than its planned instant was lost or is
  // late: it no longer counts (until a report says when it acted).
  void command_applied(std::uint64_t sequence, double arrival_s);
  // The axis reports that `command` acted from `arrival_s` in place of command `sequence`
  // (packetized predictive control: a lost or late command's slot played from an older
  // sample's horizon). A sequence never sent is remembered in its place.
  void command_played(std::uint64_t sequence, double arrival_s, double command);
  // The axis measured `position_m` at `sample_time_s` (sample `sequence`); older or repeated
  // samples than the newest are ignored.
  void measured(std::uint64_t sequence, double sample_time_s, double position_m);

  bool has_measurement() const { return has_measurement_; }
  double newest_sample_time_s() const { return state_time_s_; }
  // The predicted position at `time_s`, from the newest sample and the commands in force and in
  // flight; the measured position itself for a time at or before the sample.
  double predict_position(double time_s) const;
  // The whole predicted state at `time_s` (position, velocity, disturbance), as predict_position.
  PredictedState predict_state(double time_s) const;
  // `state` run on for `duration_s` under `command` (saturated as the axis saturates it), the
  // disturbance held: a look-ahead past the commands sent (packetized predictive control).
  PredictedState run_on(PredictedState state, double duration_s, double command) const;
  // The observer's estimate at the newest sample (velocity, disturbance; position measured).
  PredictedState estimate() const;
  // The commands remembered beside the one in force (at most kMaxPendingCommands).
  std::size_t pending_commands() const { return pending_.size(); }

  // At most this many commands are remembered while no newer sample comes; older ones fold into
  // the input in force (a bound on memory whatever the link does).
  static constexpr std::size_t kMaxPendingCommands = 4096;

 private:
  struct Command {
    std::uint64_t sequence = 0;
    double value = 0.0;
    double arrival_s = 0.0;
    bool reported = false;  // arrival_s is the axis's report, not the plan
  };
  // Whether `command` acts in a model run when the axis's reports are complete up to `known_s`
  // (its newest sample): reported, or planned after that.
  static bool counts(const Command& command, double known_s) { return command.reported || command.arrival_s > known_s; }
  // Runs `state` from `from_s` to `to_s` under the commands as the axis applies them, its reports
  // complete up to `known_s`.
  void advance(PredictedState& state, double from_s, double to_s, double known_s) const;
  // The commands that act by `time_s` become the input in force there.
  void settle_commands_until(double time_s);

  PredictionModel model_;
  double command_limit_;
  Eigen::Vector3d correction_gain_;  // the observer's, on the position innovation

  PredictedState estimate_;          // at state_time_s_, after that sample's correction
  double state_time_s_ = 0.0;
  double measured_position_m_ = 0.0;
  bool has_measurement_ = false;
  std::uint64_t newest_sample_ = 0;
  // The command in force at state_time_s_ (u(-1) = 0 before any) and those acting later.
  double input_in_force_ = 0.0;
  std::uint64_t input_sequence_ = 0;
  bool has_input_sequence_ = false;
  std::vector<Command> pending_;               // in sequence order
  mutable std::vector<const Command*> by_arrival_;  // scratch of advance(), no allocation per call
};

}  // namespace netmc::control
