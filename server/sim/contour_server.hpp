#pragma once
// The server side of a contouring job in virtual time: the uplink of each axis (netsim delays
// or drops feedback before the server consumes it), the event-driven cycle with its deadline,
// the contouring controller, and the iteration metrics. In-process runs and netmc-server's
// lockstep mode drive the same object, so both give bit-identical results.

#include <Eigen/Dense>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "control/group/contour_group.hpp"
#include "control/delay_compensation/axis_state_predictor.hpp"
#include "netsim/delayed_channel.hpp"
#include "server/sim/axis_endpoint.hpp"
#include "server/sim/contour_job.hpp"
#include "server/sim/cycle_listener.hpp"
#include "server/sim/delay_statistics.hpp"
#include "server/sim/iteration_metrics.hpp"

namespace netmc::sim {

struct CycleCommand {
  control::AxisVector command;  // one per axis, in the group's order
  double send_time_s = 0.0;     // when the setpoints leave the server (virtual time)
  // With delay compensation, the instant the commands are meant to act (the axes hold an early
  // one until then); -inf: on arrival.
  double acts_at_s = -std::numeric_limits<double>::infinity();
  // Packetized predictive control: per axis, horizon_length commands (axis-major), the first
  // the command itself, each next one meant to act a period after the one before. 0: none.
  std::size_t horizon_length = 0;
  std::vector<double> horizon;
  bool diverged = false;        // the loop is unstable: stop the iteration
  // The contour-error limit was crossed (diverged too): a realtime job fails with this message.
  std::string limit_exceeded;
};

class ContourServer {
 public:
  explicit ContourServer(const ContourJob& job);

  // Returns the start position every axis must rest at for this iteration.
  control::AxisVector begin_iteration(std::size_t iteration);
  // Feedback `cycle` of `axis`, sampled at `sample_time_s`, enters the uplink.
  void submit_feedback(std::size_t axis, std::uint64_t cycle, double sample_time_s,
                       const AxisSample& sample);
  // When cycle k will be computed (virtual time): when the last feedback k arrives through the
  // uplink, or at the deadline. A wall-clock server waits until then.
  double compute_time(std::uint64_t cycle) const;
  // Computes cycle k once the feedback of cycle k has been submitted for every axis.
  CycleCommand compute_cycle(std::uint64_t cycle);
  // A wall-clock server measures the computation delay of the cycle just computed (from the
  // last feedback's arrival to the setpoints' departure); virtual time uses the job's value.
  void correct_compute_delay(double measured_s);
  // Setpoints applied by `axis`, for the loop-delay statistics.
  void record_applied(std::size_t axis, const std::vector<AppliedSetpoint>& applied);
  // Packetized predictive control: the axes' counters of the iteration (AxisEndpoint), summed.
  void record_playout(std::uint64_t horizon_cycles, std::uint64_t held_cycles);
  // Closes the iteration; `lost` and `stale` are the axes' downlink counters.
  IterationRecord end_iteration(std::uint64_t lost_setpoints, std::uint64_t stale_setpoints);

  // A live view of the cycles (netmc-server's console); none by default. It changes nothing the
  // loop computes: lockstep and in-process results stay the same with or without one.
  void set_cycle_listener(std::shared_ptr<CycleListener> listener) { listener_ = std::move(listener); }

  std::string controller_description() const { return controller_->describe(); }
  std::size_t cycles() const { return cycles_; }

 private:
  // An axis that covers less than this fraction of its reference's range marks a run that did
  // not follow (IterationMetrics::did_not_follow).
  static constexpr double kCoverageFraction = 0.5;
  bool did_not_follow() const;
  // The setpoints' planned travel, from the server to the instant they act: the longest of the
  // downlink delays the axes reported lately (0 before the first), so that setpoints arrive
  // before their instant and act exactly then. (With the 95th percentile, 1 setpoint in 20 came
  // late: adrc+pidccc lost stability from 95 ms of U(0.3 ms, max) and adrc+ilccc's e_max grew
  // from 45 ms; with the longest, from 120 ms and 50 ms.)
  double playout_delay_s() const;

  // Delay compensation (job.compensation): one predictor per axis, the positions and the
  // reference the controller is given instead of the newest measurement and the reference at t_k.
  std::vector<control::AxisStatePredictor> predictors_;
  control::AxisVector predicted_;
  control::GroupReference predicted_reference_;
  static constexpr std::size_t kDownlinkWindow = 256;  // the delays the longest is taken of
  static constexpr double kMaxPlannedTravelS = DelayCompensation::kMaxPlayoutS;  // netsim's bound on a delay
  std::vector<double> downlink_delays_s_;   // a ring of the newest kDownlinkWindow
  std::size_t downlink_next_ = 0;
  DelayStatistics feedback_age_;
  // Packetized predictive control: the commands of cycle k meant for the next instants, computed
  // by a copy of the controller on the predicted positions. Every command acts at an instant of
  // one grid, slot_origin_s_ + slot * h (slots increase), so the axis's playout and the
  // predictor's slots agree.
  void plan_horizon(std::uint64_t cycle, double acts_at, CycleCommand& out);
  // When the planned instant leaps ahead by more than a period (the planned travel grew: longer
  // delays reported), the controller is stepped through the instants it skipped, on the positions
  // predicted there and the reference there, before it computes the command for the new instant.
  // Its observers and filters then see a time line without a jump; with a jump, a leap of 100 ms
  // in iteration 1 under U(0.3, 200) ms (the first long delays reported) stepped ADRC's observer
  // input and sent commands of 70 times the rated one (adrc diverged in 3 of 5 seeds).
  void catch_up(std::uint64_t cycle, double acts_at);
  double last_acts_at_s_ = std::numeric_limits<double>::infinity();  // none yet this iteration
  static constexpr std::size_t kMaxCatchUpSteps = 1000;  // 5 s at h = 5 ms: bounds a cycle's work
  std::size_t horizon_ = 0;  // commands per setpoint; 0 without packets
  double slot_origin_s_ = 0.0;
  std::int64_t last_slot_ = -1;
  std::vector<control::PredictedState> lookahead_states_;  // reused each cycle
  control::AxisVector lookahead_predicted_;
  control::GroupReference lookahead_reference_;
  struct SentHorizon {
    std::uint64_t cycle = 0;
    std::size_t length = 0;
    std::vector<double> commands;  // axis-major, as CycleCommand::horizon
  };
  static constexpr std::size_t kSentHorizons = 1024;  // reports of older setpoints find none
  std::vector<SentHorizon> sent_horizons_;

  ContourJob job_;
  std::shared_ptr<const control::GroupContour> contour_;
  std::unique_ptr<control::GroupController> controller_;
  std::vector<netsim::DelayedChannel<double>> uplinks_;
  std::vector<netsim::DelayedChannel<double>::Delivery> arrived_;  // one cycle's, reused
  std::size_t cycles_;
  double evaluation_start_;

  // State of the current iteration.
  IterationRecord record_;
  control::GroupReference reference_;  // one cycle's, reused
  control::AxisVector server_measurement_;
  control::AxisVector true_position_;
  control::AxisVector measured_;
  std::vector<std::int64_t> newest_sequence_;
  DelayStatistics tau_, tau_sc_, tau_cc_, tau_ca_;  // bounded however long the iteration
  double squared_error_sum_ = 0.0;
  double steady_squared_sum_ = 0.0;
  std::size_t steady_samples_ = 0;
  std::vector<double> tracking_squares_, command_squares_, steady_command_squares_;
  // Per axis, over the iteration: where the reference and the axis went (did it follow?).
  control::AxisVector reference_min_, reference_max_, position_min_, position_max_;
  double compute_time_ = 0.0;
  std::size_t samples_ = 0;
  std::array<double, control::kMaxControllerEstimates> last_estimates_{};
  std::shared_ptr<CycleListener> listener_;
  double latest_tau_s_ = -1.0;  // axis 0's, for the listener
};

}  // namespace netmc::sim
