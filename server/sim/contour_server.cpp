#include "server/sim/contour_server.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "server/sim/random_streams.hpp"

namespace netmc::sim {

ContourServer::ContourServer(const ContourJob& job)
    : job_((job.validate(), job)),
      contour_(job_.contour()),
      controller_(job_.make_controller()),
      cycles_(job_.cycles()),
      evaluation_start_(job_.evaluation_start()) {
  for (std::size_t axis = 0; axis < job_.axes.size(); ++axis) {
    uplinks_.emplace_back(netsim::LinkModel(job_.uplink.delay->clone(), job_.uplink.loss->clone(),
                                            job_stream(job_.seed, StreamKind::uplink, axis, 0)));
  }
  if (job_.compensation) {
    for (const auto& model : job_.compensation->axis_models) {
      predictors_.emplace_back(model, job_.sample_period_s, job_.command_limit);
    }
    if (job_.compensation->horizon > 1) {
      horizon_ = job_.compensation->horizon;
      slot_origin_s_ = job_.compute_delay_s;
      sent_horizons_.resize(kSentHorizons);
    }
  }
}

double ContourServer::playout_delay_s() const {
  // A configured playout delay holds from the first cycle, before any report has come back
  // (Luck and Ray's buffer); the axes' reports plan longer when the link is slower than it.
  const double configured = job_.compensation ? job_.compensation->playout_s : 0.0;
  return downlink_delays_s_.empty()
             ? configured
             : std::max(configured, *std::max_element(downlink_delays_s_.begin(), downlink_delays_s_.end()));
}

control::AxisVector ContourServer::begin_iteration(std::size_t iteration) {
  // Every iteration starts from the same initial state; nothing of the previous one is in flight.
  const control::AxisVector start = job_.start_position();
  const std::size_t axes = uplinks_.size();
  for (std::size_t axis = 0; axis < uplinks_.size(); ++axis) {
    uplinks_[axis].reset(job_stream(job_.seed, StreamKind::uplink, axis, iteration));
  }
  controller_->begin_iteration(start, cycles_);
  for (std::size_t axis = 0; axis < predictors_.size(); ++axis) {
    predictors_[axis].reset(start[static_cast<Eigen::Index>(axis)]);
  }
  predicted_ = start;
  feedback_age_.clear();
  last_slot_ = -1;
  last_acts_at_s_ = std::numeric_limits<double>::infinity();
  for (auto& sent : sent_horizons_) sent.length = 0;

  record_ = IterationRecord{};
  record_.metrics.iteration = iteration;
  latest_tau_s_ = -1.0;
  record_.metrics.estimate_names = controller_->estimate_names();
  last_estimates_ = {};
  for (auto* values : {&record_.metrics.tracking_rms_m, &record_.metrics.tracking_max_m,
                       &record_.metrics.command_rms, &record_.metrics.command_rms_steady,
                       &tracking_squares_, &command_squares_, &steady_command_squares_}) {
    values->assign(axes, 0.0);
  }
  if (job_.record_traces) record_.trace.resize(cycles_);
  server_measurement_ = start;
  true_position_ = start;  // until the first feedback (a realtime cycle may run without it)
  measured_ = start;
  newest_sequence_.assign(uplinks_.size(), -1);
  tau_.clear();
  tau_sc_.clear();
  tau_cc_.clear();
  tau_ca_.clear();
  reference_min_ = reference_max_ = position_min_ = position_max_ = start;
  squared_error_sum_ = 0.0;
  steady_squared_sum_ = 0.0;
  steady_samples_ = 0;
  compute_time_ = 0.0;
  samples_ = 0;
  return start;
}

void ContourServer::submit_feedback(std::size_t axis, std::uint64_t cycle, double sample_time_s,
                                    const AxisSample& sample) {
  const auto i = static_cast<Eigen::Index>(axis);
  true_position_[i] = sample.true_position_m;
  measured_[i] = sample.measured_m;
  if (!uplinks_[axis].send(sample_time_s, cycle, sample.measured_m)) {
    ++record_.metrics.lost_feedback;
  }
}

double ContourServer::compute_time(std::uint64_t cycle) const {
  const double t = static_cast<double>(cycle) * job_.sample_period_s;
  double ready = t;
  for (const auto& uplink : uplinks_) {
    const auto arrival = uplink.arrival_of(cycle);
    if (!arrival || *arrival > t + job_.deadline()) return std::max(compute_time_, t + job_.deadline());
    ready = std::max(ready, *arrival);
  }
  return std::max(compute_time_, ready);
}

CycleCommand ContourServer::compute_cycle(std::uint64_t cycle) {
  IterationMetrics& m = record_.metrics;
  const double t = static_cast<double>(cycle) * job_.sample_period_s;
  contour_->sample(t, reference_);
  const control::GroupReference& reference = reference_;

  // Event-driven: cycle k is computed when feedback k of every axis is in, or at the deadline
  // with the newest feedback the server holds. Only messages of cycles <= k are in flight.
  const double deadline = t + job_.deadline();
  bool complete = true;
  double last_arrival = t;
  for (std::size_t axis = 0; axis < uplinks_.size(); ++axis) {
    bool arrived = false;
    uplinks_[axis].receive_until(deadline, arrived_);
    for (const auto& delivery : arrived_) {
      const auto sequence = static_cast<std::int64_t>(delivery.sequence);
      if (delivery.sequence < cycle) ++m.late_feedback;  // missed its own deadline
      if (sequence > newest_sequence_[axis]) {
        newest_sequence_[axis] = sequence;
        server_measurement_[static_cast<Eigen::Index>(axis)] = delivery.payload;
        // The feedback's own time stamp: the instant the axis sampled it, t_j on the job's time
        // line (a realtime node samples on the grid the server's t0 and its clock offset give it).
        if (!predictors_.empty()) {
          predictors_[axis].measured(delivery.sequence, static_cast<double>(delivery.sequence) * job_.sample_period_s,
                                     delivery.payload);
        }
      }
      if (delivery.sequence == cycle) {
        arrived = true;
        last_arrival = std::max(last_arrival, delivery.arrival_time_s);
        tau_sc_.add(delivery.arrival_time_s - t);
      }
    }
    complete = complete && arrived;
  }
  if (!complete) ++m.deadline_misses;
  compute_time_ = std::max(compute_time_, complete ? last_arrival : deadline);

  CycleCommand out;
  out.send_time_s = compute_time_ + job_.compute_delay_s;
  const control::GroupCycle* computed = nullptr;
  if (predictors_.empty()) {
    computed = &controller_->step(cycle, reference, server_measurement_);
  } else {
    // The controller acts on the instant its command will act: each axis's state predicted from
    // its newest sample over that sample's age plus the setpoint's expected travel, and the
    // reference there. Without delay the instant is t_k and nothing changes.
    double acts_at = out.send_time_s + playout_delay_s();
    // With packets the instant is on the grid; without the predictor it is the cycle's own.
    std::int64_t slot = static_cast<std::int64_t>(cycle);
    if (horizon_ > 0) {
      const double h = job_.sample_period_s;
      if (job_.compensation->predict_delay) {
        // A bounded plan (kMaxPlannedTravelS) keeps the slot far inside an int64.
        slot = std::max(slot, static_cast<std::int64_t>(std::ceil((acts_at - slot_origin_s_) / h - 1e-9)));
      }
      slot = std::max(slot, last_slot_ + 1);
      last_slot_ = slot;
      acts_at = slot_origin_s_ + static_cast<double>(slot) * h;
    }
    out.acts_at_s = acts_at;
    catch_up(cycle, acts_at);
    for (std::size_t axis = 0; axis < predictors_.size(); ++axis) {
      const auto i = static_cast<Eigen::Index>(axis);
      const auto& predictor = predictors_[axis];
      predicted_[i] = predictor.has_measurement() ? predictor.predict_position(acts_at) : server_measurement_[i];
      if (predictor.has_measurement()) feedback_age_.add(compute_time_ - predictor.newest_sample_time_s());
    }
    const control::GroupReference* planned = &reference;
    if (acts_at != t) {
      contour_->sample(acts_at, predicted_reference_);
      planned = &predicted_reference_;
    }
    computed = &controller_->step(cycle, *planned, predicted_);
    for (std::size_t axis = 0; axis < predictors_.size(); ++axis) {
      predictors_[axis].command_sent(static_cast<std::uint64_t>(slot), computed->command[static_cast<Eigen::Index>(axis)],
                                     acts_at);
    }
    if (horizon_ > 0 && computed->command.allFinite()) {
      out.command = computed->command;
      plan_horizon(cycle, acts_at, out);
    }
  }
  const control::GroupCycle& step = *computed;
  out.command = step.command;
  // Only a controller with internal estimates has any to keep (most cycles copy nothing).
  if (!record_.metrics.estimate_names.empty()) last_estimates_ = step.estimates;
  tau_cc_.add(job_.compute_delay_s);

  // Metrics from the true plant state and the exact contour.
  const double contour_error = contour_->contour_error(true_position_, reference);
  if (!(std::abs(contour_error) <= job_.divergence_limit_m) || !step.command.allFinite()) {
    m.diverged = true;
    m.diverged_at_s = t;
    out.diverged = true;
    return out;
  }
  if (std::abs(contour_error) > job_.contour_error_limit_m) {
    // Named by the axis farthest from its reference: where to look first.
    Eigen::Index worst = 0;
    (reference.position - true_position_).cwiseAbs().maxCoeff(&worst);
    m.diverged = true;
    m.diverged_at_s = t;
    m.stop_reason = fmt::format(
        "contour error {:.3f} mm beyond the limit {:.3f} mm at cycle {} (t = {:.3f} s); axis {} {:.3f} mm from its "
        "reference",
        std::abs(contour_error) * 1e3, job_.contour_error_limit_m * 1e3, cycle, t,
        job_.axis_names[static_cast<std::size_t>(worst)],
        (reference.position[worst] - true_position_[worst]) * 1e3);
    out.diverged = true;
    out.limit_exceeded = m.stop_reason;
    return out;
  }
  ++samples_;
  m.e_max_m = std::max(m.e_max_m, std::abs(contour_error));
  m.e_sum_m += std::abs(contour_error);
  squared_error_sum_ += contour_error * contour_error;
  if (t >= evaluation_start_) {
    steady_squared_sum_ += contour_error * contour_error;
    ++steady_samples_;
    m.e_max_steady_m = std::max(m.e_max_steady_m, std::abs(contour_error));
  }
  for (std::size_t axis = 0; axis < uplinks_.size(); ++axis) {
    const auto i = static_cast<Eigen::Index>(axis);
    // Where the reference and the axis went (did it follow?), as scalars: cheaper per cycle.
    reference_min_[i] = std::min(reference_min_[i], reference.position[i]);
    reference_max_[i] = std::max(reference_max_[i], reference.position[i]);
    position_min_[i] = std::min(position_min_[i], true_position_[i]);
    position_max_[i] = std::max(position_max_[i], true_position_[i]);
    const double tracking = reference.position[i] - true_position_[i];
    tracking_squares_[axis] += tracking * tracking;
    m.tracking_max_m[axis] = std::max(m.tracking_max_m[axis], std::abs(tracking));
    command_squares_[axis] += step.command[i] * step.command[i];
    if (t >= evaluation_start_) {
      const double applied = std::min(std::abs(step.command[i]), job_.command_limit);
      steady_command_squares_[axis] += applied * applied;
    }
  }
  if (job_.record_traces) {
    CycleTrace& row = record_.trace[cycle];
    row.time_s = t;
    row.reference_m = reference.position;
    row.position_m = true_position_;
    row.measured_m = measured_;
    row.axis_command = step.axis_command;
    row.command = step.command;
    row.contour_error_m = contour_error;
    row.contour_error_estimate_m = step.estimate.contour_error;
    row.coupling_command = step.coupling_command;
    if (!record_.metrics.estimate_names.empty()) row.estimates = step.estimates;
  }
  if (listener_) {
    LiveCycle live;
    live.iteration = record_.metrics.iteration;
    live.cycle = cycle;
    live.time_s = t;
    live.reference_m = reference.position;
    live.position_m = true_position_;
    live.contour_error_m = contour_error;
    live.command = step.command;
    live.latest_tau_s = latest_tau_s_;
    listener_->on_cycle(live);
  }
  return out;
}

void ContourServer::catch_up(std::uint64_t cycle, double acts_at) {
  const double h = job_.sample_period_s;
  const double last = last_acts_at_s_;
  last_acts_at_s_ = acts_at;
  if (!(acts_at - last > 1.5 * h)) return;
  std::size_t steps = 0;
  for (double at = last + h; at < acts_at - 0.5 * h && steps < kMaxCatchUpSteps; at += h, ++steps) {
    for (std::size_t axis = 0; axis < predictors_.size(); ++axis) {
      const auto i = static_cast<Eigen::Index>(axis);
      const auto& predictor = predictors_[axis];
      predicted_[i] = predictor.has_measurement() ? predictor.predict_position(at) : server_measurement_[i];
    }
    contour_->sample(at, predicted_reference_);
    controller_->step(cycle, predicted_reference_, predicted_);
  }
}

void ContourServer::plan_horizon(std::uint64_t cycle, double acts_at, CycleCommand& out) {
  const std::size_t axes = predictors_.size();
  const std::size_t length = std::min<std::size_t>(horizon_, cycles_ - cycle);
  out.horizon_length = length;
  out.horizon.assign(axes * length, 0.0);
  for (std::size_t axis = 0; axis < axes; ++axis) out.horizon[axis * length] = out.command[static_cast<Eigen::Index>(axis)];
  if (length > 1) {
    // The law itself, run ahead on its own copy: each next command from the positions predicted
    // with the ones before it, for the reference at its instant (Bemporad 1998).
    // The model runs on from the state predicted at the first instant, a period at a time under
    // each command (no other command acts after that instant: the grid's slots increase).
    auto ahead = controller_->clone();
    lookahead_states_.resize(axes);
    for (std::size_t axis = 0; axis < axes; ++axis) lookahead_states_[axis] = predictors_[axis].predict_state(acts_at);
    lookahead_predicted_ = predicted_;
    const double h = job_.sample_period_s;
    for (std::size_t j = 1; j < length; ++j) {
      const double at = acts_at + static_cast<double>(j) * h;
      for (std::size_t axis = 0; axis < axes; ++axis) {
        const auto& predictor = predictors_[axis];
        auto& state = lookahead_states_[axis];
        state = predictor.run_on(state, h, out.horizon[axis * length + j - 1]);
        if (predictor.has_measurement()) lookahead_predicted_[static_cast<Eigen::Index>(axis)] = state.position_m;
      }
      contour_->sample(at, lookahead_reference_);
      const control::GroupCycle& step = ahead->step(cycle + j, lookahead_reference_, lookahead_predicted_);
      // Saturated as the axis would: a prediction is no reason to trip the operator's limit.
      for (std::size_t axis = 0; axis < axes; ++axis) {
        out.horizon[axis * length + j] =
            std::clamp(step.command[static_cast<Eigen::Index>(axis)], -job_.command_limit, job_.command_limit);
      }
    }
  }
  SentHorizon& sent = sent_horizons_[cycle % kSentHorizons];
  sent.cycle = cycle;
  sent.length = length;
  sent.commands = out.horizon;
}

void ContourServer::record_playout(std::uint64_t horizon_cycles, std::uint64_t held_cycles) {
  if (horizon_ == 0) return;
  record_.metrics.packets = true;
  record_.metrics.horizon_cycles = horizon_cycles;
  record_.metrics.held_cycles = held_cycles;
}

void ContourServer::correct_compute_delay(double measured_s) {
  tau_cc_.replace_last(measured_s);
}

void ContourServer::record_applied(std::size_t axis, const std::vector<AppliedSetpoint>& applied) {
  for (const auto& a : applied) {
    const double loop_delay =
        a.arrival_time_s - static_cast<double>(a.sequence) * job_.sample_period_s;
    tau_.add(loop_delay);
    tau_ca_.add(a.arrival_time_s - a.send_time_s);
    if (horizon_ > 0) {
      // What acted and when, in its slot of the grid: the setpoint's own command or one of its
      // horizon's (a report names a cycle and an index; the command is the one sent then).
      const SentHorizon& sent = sent_horizons_[a.sequence % kSentHorizons];
      const double slot = std::round((a.arrival_time_s - slot_origin_s_) / job_.sample_period_s);
      if (sent.length > 0 && sent.cycle == a.sequence && a.horizon_index < sent.length && slot >= 0.0 &&
          slot <= static_cast<double>(last_slot_ + static_cast<std::int64_t>(horizon_))) {
        predictors_[axis].command_played(static_cast<std::uint64_t>(slot), a.arrival_time_s,
                                         sent.commands[axis * sent.length + a.horizon_index]);
      }
    } else if (!predictors_.empty()) {
      predictors_[axis].command_applied(a.sequence, a.arrival_time_s);
    }
    if (!predictors_.empty()) {
      // A node's report is checked like any sample from the network: a travel that is no
      // delay (not finite, negative, beyond a minute) plans nothing.
      const double travel = a.network_arrival_s - a.send_time_s;
      const bool is_delay = travel >= 0.0 && travel <= kMaxPlannedTravelS;
      if (is_delay && downlink_delays_s_.size() < kDownlinkWindow) {
        downlink_delays_s_.push_back(travel);
      } else if (is_delay) {
        downlink_delays_s_[downlink_next_] = travel;
        downlink_next_ = (downlink_next_ + 1) % kDownlinkWindow;
      }
    }
    if (axis == 0) latest_tau_s_ = loop_delay;
    if (job_.record_traces && axis == 0 && a.sequence < record_.trace.size()) {
      record_.trace[a.sequence].tau_s = loop_delay;
    }
  }
}

bool ContourServer::did_not_follow() const {
  // The reference's extent: its largest range on any axis over the iteration.
  const control::AxisVector reference_range = reference_max_ - reference_min_;
  const double extent = reference_range.maxCoeff();
  if (!(extent > 0.0)) return false;  // a reference that stands still: nothing to follow
  const control::AxisVector position_range = position_max_ - position_min_;
  for (Eigen::Index i = 0; i < reference_range.size(); ++i) {
    // An axis that was to move (by more than 1 % of the extent) and covered less than half of
    // its reference's range. A tracking error alone would not do: a contouring controller may
    // trail the reference's time on purpose (the thesis's case B starts away from the path and
    // reaches it through its initialization filter, tracking errors of 80 mm on a 40 mm circle).
    if (reference_range[i] > 0.01 * extent && position_range[i] < kCoverageFraction * reference_range[i]) return true;
  }
  return false;
}

IterationRecord ContourServer::end_iteration(std::uint64_t lost_setpoints,
                                             std::uint64_t stale_setpoints) {
  IterationMetrics& m = record_.metrics;
  if (job_.record_traces) record_.trace.resize(samples_);
  const auto n = static_cast<double>(std::max<std::size_t>(samples_, 1));
  m.e_rms_m = std::sqrt(squared_error_sum_ / n);
  m.steady_samples = steady_samples_;
  if (steady_samples_ > 0) m.e_rms_steady_m = std::sqrt(steady_squared_sum_ / static_cast<double>(steady_samples_));
  for (std::size_t axis = 0; axis < uplinks_.size(); ++axis) {
    m.tracking_rms_m[axis] = std::sqrt(tracking_squares_[axis] / n);
    m.command_rms[axis] = std::sqrt(command_squares_[axis] / n);
    if (steady_samples_ > 0) {
      m.command_rms_steady[axis] =
          std::sqrt(steady_command_squares_[axis] / static_cast<double>(steady_samples_));
    }
  }
  m.did_not_follow = !m.diverged && samples_ > 0 && did_not_follow();
  m.final_estimates.assign(last_estimates_.begin(),
                           last_estimates_.begin() + static_cast<std::ptrdiff_t>(m.estimate_names.size()));
  m.lost_setpoints = lost_setpoints;
  m.stale_setpoints = stale_setpoints;
  m.tau_mean_s = tau_.mean();
  m.tau_max_s = tau_.max();
  m.tau_p50_s = tau_.percentile(0.50);
  m.tau_p99_s = tau_.percentile(0.99);
  const auto summarize = [](const DelayStatistics& values, double& mean_s, double& p99_s, double& max_s) {
    mean_s = values.mean();
    p99_s = values.percentile(0.99);
    max_s = values.max();
  };
  summarize(tau_sc_, m.tau_sc_mean_s, m.tau_sc_p99_s, m.tau_sc_max_s);
  summarize(tau_cc_, m.tau_cc_mean_s, m.tau_cc_p99_s, m.tau_cc_max_s);
  summarize(tau_ca_, m.tau_ca_mean_s, m.tau_ca_p99_s, m.tau_ca_max_s);
  if (horizon_ > 0) m.packets = true;
  if (!predictors_.empty()) {
    m.compensated = true;
    summarize(feedback_age_, m.feedback_age_mean_s, m.feedback_age_p99_s, m.feedback_age_max_s);
  }
  controller_->end_iteration();
  return std::move(record_);
}

}  // namespace netmc::sim
