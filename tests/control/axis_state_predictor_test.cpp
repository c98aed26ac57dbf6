// The delay compensator's state predictor against an independent integration of the axis it
// models: exact once its observer has converged on an axis that is its model, the measurement
// itself over a zero horizon, the axis's own rules for which command acts (arrival order, stale
// commands dropped, saturation).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <deque>
#include <tuple>
#include <vector>

#include "control/delay_compensation/axis_state_predictor.hpp"

namespace netmc::control {
namespace {

// The modelled axis, x'' = a x' + b u + d, integrated by RK4 in small steps: a second method.
struct TrueAxis {
  double a, b, d;
  double position = 0.0, velocity = 0.0;
  double coulomb = 0.0, scale = 1e-3;  // Coulomb friction c tanh(v / scale)
  void run(double duration_s, double input) {
    const int steps = 200;
    const double dt = duration_s / steps;
    for (int i = 0; i < steps; ++i) {
      const auto acc = [&](double v) { return a * v + b * input + d - coulomb * std::tanh(v / scale); };
      const double k1x = velocity, k1v = acc(velocity);
      const double k2x = velocity + 0.5 * dt * k1v, k2v = acc(velocity + 0.5 * dt * k1v);
      const double k3x = velocity + 0.5 * dt * k2v, k3v = acc(velocity + 0.5 * dt * k2v);
      const double k4x = velocity + dt * k3v, k4v = acc(velocity + dt * k3v);
      position += dt / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
      velocity += dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
  }
};

TEST(PredictionModel, AdvanceMatchesTheClosedFormOfTheDoubleIntegrator) {
  const PredictionModel model{.damping_per_s = 0.0, .input_gain = 20.0, .observer_bandwidth_rad_s = 100.0};
  PredictedState state{0.01, 0.02, 0.3};
  advance_model(model, state, 0.015, 0.05);
  const double acc = 20.0 * 0.05 + 0.3;
  EXPECT_NEAR(state.position_m, 0.01 + 0.02 * 0.015 + 0.5 * acc * 0.015 * 0.015, 1e-15);
  EXPECT_NEAR(state.velocity_m_s, 0.02 + acc * 0.015, 1e-15);
  EXPECT_EQ(state.disturbance_m_s2, 0.3);  // held
}

TEST(PredictionModel, AdvanceWithDampingMatchesRk4) {
  const PredictionModel model{.damping_per_s = -20.0, .input_gain = 20.0, .observer_bandwidth_rad_s = 100.0};
  PredictedState state{0.0, 0.01, -0.06};
  TrueAxis axis{-20.0, 20.0, -0.06, 0.0, 0.01};
  advance_model(model, state, 0.03, 0.2);
  axis.run(0.03, 0.2);
  EXPECT_NEAR(state.position_m, axis.position, 1e-12);
  EXPECT_NEAR(state.velocity_m_s, axis.velocity, 1e-12);
}

// A closed loop in virtual time: commands reach the axis `delay_s` after they are sent at t_k;
// the predictor gets every sample at once and every command's true arrival.
struct DelayedLoop {
  explicit DelayedLoop(double coulomb = 0.0)
      : predictor(PredictionModel{.damping_per_s = -20.0, .input_gain = 20.0, .coulomb_m_s2 = coulomb,
                                  .coulomb_velocity_scale_m_s = 1e-3, .observer_bandwidth_rad_s = 100.0},
                  0.005) {
    axis.coulomb = coulomb;
  }
  double h = 0.005, delay_s = 0.0175;
  TrueAxis axis{-20.0, 20.0, -0.05};
  AxisStatePredictor predictor;
  std::deque<std::tuple<double, double, std::uint64_t>> in_flight;  // arrival, command, sequence
  double input = 0.0;

  // One period from t_k: sample, then a command, then the axis runs to t_k+1 applying arrivals.
  void cycle(std::uint64_t k, double command) {
    const double t = static_cast<double>(k) * h;
    predictor.measured(k, t, axis.position);
    predictor.command_sent(k, command, t + delay_s);
    in_flight.emplace_back(t + delay_s, command, k);
    double now = t;
    while (!in_flight.empty() && std::get<0>(in_flight.front()) < t + h) {
      const auto [arrival, value, sequence] = in_flight.front();
      axis.run(arrival - now, input);
      now = arrival;
      input = value;
      predictor.command_applied(sequence, arrival);  // the axis's report, with the next sample
      in_flight.pop_front();
    }
    axis.run(t + h - now, input);
  }
};

// Runs `loop` 400 periods under a sine command and returns (predicted, true) position at the
// instant the last command acts.
std::pair<double, double> predict_after_sine(DelayedLoop& loop) {
  loop.predictor.reset(0.0);
  std::vector<double> commands;
  for (std::uint64_t k = 0; k < 400; ++k) commands.push_back(0.02 * std::sin(0.03 * static_cast<double>(k)));
  for (std::uint64_t k = 0; k + 1 < commands.size(); ++k) loop.cycle(k, commands[k]);
  // At the last sample t_N: where will the axis be when command N (sent now) acts?
  const std::uint64_t last = commands.size() - 1;
  const double t = static_cast<double>(last) * loop.h;
  loop.predictor.measured(last, t, loop.axis.position);
  const double predicted = loop.predictor.predict_position(t + loop.delay_s);
  // The truth: the axis run on from t_N with the commands still in flight.
  TrueAxis truth = loop.axis;
  double now = t, input = loop.input;
  for (const auto& [arrival, command, sequence] : loop.in_flight) {
    truth.run(arrival - now, input);
    now = arrival;
    input = command;
  }
  truth.run(t + loop.delay_s - now, input);
  EXPECT_GT(std::abs(truth.position - loop.axis.position), 1e-5);  // there is something to predict
  return {predicted, truth.position};
}

TEST(AxisStatePredictor, PredictsAnAxisThatIsItsModelExactlyOverTheDelay) {
  DelayedLoop loop;
  const auto [predicted, truth] = predict_after_sine(loop);
  EXPECT_NEAR(predicted, truth, 1e-9);
  EXPECT_NEAR(loop.predictor.estimate().disturbance_m_s2, -0.05, 1e-9);
}

// The worst prediction error over a run that reverses many times, of an axis with seed001's X
// friction (60 mm/s^2 over a 1 mm/s tanh), by a predictor whose model has `modelled` of it.
double worst_error_through_reversals(double modelled) {
  DelayedLoop loop(modelled);
  loop.axis.coulomb = 0.060;
  loop.delay_s = 0.015;  // three periods: the truth is the sample three cycles on
  loop.predictor.reset(0.0);
  std::vector<double> predicted, sampled;
  for (std::uint64_t k = 0; k < 600; ++k) {
    sampled.push_back(loop.axis.position);
    loop.cycle(k, 0.004 * std::sin(0.05 * static_cast<double>(k)));
    predicted.push_back(loop.predictor.predict_position(static_cast<double>(k) * loop.h + loop.delay_s));
  }
  double worst = 0.0;
  for (std::size_t k = 100; k + 3 < sampled.size(); ++k) worst = std::max(worst, std::abs(predicted[k] - sampled[k + 3]));
  return worst;
}

TEST(AxisStatePredictor, PredictsThroughCoulombFrictionWhenTheModelHasIt) {
  const double modelled = worst_error_through_reversals(0.060);
  const double unmodelled = worst_error_through_reversals(0.0);
  EXPECT_LT(modelled, 1e-8);
  // Without it the observer lags each reversal: the test tells the two apart.
  EXPECT_GT(unmodelled, 100.0 * modelled);
}

TEST(AxisStatePredictor, ZeroHorizonReturnsTheMeasurementItself) {
  AxisStatePredictor predictor(PredictionModel{.damping_per_s = 0.0, .input_gain = 20.0, .observer_bandwidth_rad_s = 100.0}, 0.005);
  predictor.reset(0.05);
  predictor.measured(0, 0.0, 0.05);
  predictor.command_sent(0, 0.3, 0.0);
  predictor.measured(1, 0.005, 0.0500123456789);
  EXPECT_EQ(predictor.predict_position(0.005), 0.0500123456789);
  EXPECT_EQ(predictor.predict_position(0.001), 0.0500123456789);  // before the sample: no prediction
}

TEST(AxisStatePredictor, AStaleCommandArrivingAfterANewerOneDoesNotAct) {
  // Ideal observer state at rest (no correction: the measurement equals the model at rest).
  const PredictionModel model{.damping_per_s = 0.0, .input_gain = 10.0, .observer_bandwidth_rad_s = 100.0};
  AxisStatePredictor predictor(model, 0.005);
  predictor.reset(0.0);
  predictor.measured(0, 0.0, 0.0);
  predictor.command_sent(1, 1.0, 0.010);   // arrives after the newer one below: dropped at the axis
  predictor.command_sent(2, -0.5, 0.004);
  // From 0.004 s the axis has -0.5 in force; 1.0 never acts.
  PredictedState expected{0.0, 0.0, 0.0};
  advance_model(model, expected, 0.004, 0.0);
  advance_model(model, expected, 0.016, -0.5);
  EXPECT_NEAR(predictor.predict_position(0.020), expected.position_m, 1e-15);
}

TEST(AxisStatePredictor, ACommandTheAxisNeverReportedStopsCountingOnceANewerSamplePassedItsInstant) {
  const PredictionModel model{.damping_per_s = 0.0, .input_gain = 10.0, .observer_bandwidth_rad_s = 100.0};
  AxisStatePredictor predictor(model, 0.005);
  predictor.reset(0.0);
  predictor.measured(0, 0.0, 0.0);
  predictor.command_sent(0, 1.0, 0.004);  // lost on the way: never reported
  const double while_in_flight = predictor.predict_position(0.010);
  EXPECT_GT(while_in_flight, 0.0);  // planned after the newest sample: assumed to act
  predictor.measured(1, 0.005, 0.0);  // the axis did not move: its reports up to 5 ms lack it
  EXPECT_EQ(predictor.predict_position(0.010), 0.0);
  // A late report brings it back, from when it acted.
  predictor.command_applied(0, 0.007);
  PredictedState expected{0.0, 0.0, predictor.estimate().disturbance_m_s2};
  advance_model(model, expected, 0.002, 0.0);
  advance_model(model, expected, 0.003, 1.0);
  EXPECT_NEAR(predictor.predict_position(0.010), expected.position_m, 1e-15);
}

TEST(AxisStatePredictor, APlayedCommandTakesTheSlotOfTheOneThatDidNotComeAndRunOnContinuesThePrediction) {
  // Packets: slot 1's own command (0.8) was lost; the axis played 0.3 there from slot 0's horizon,
  // from 6 ms; slot 2 was never sent, the axis played -0.2 in it from 11 ms.
  const PredictionModel model{.damping_per_s = -2.0, .input_gain = 10.0, .observer_bandwidth_rad_s = 100.0};
  AxisStatePredictor predictor(model, 0.005);
  predictor.reset(0.0);
  predictor.measured(0, 0.0, 0.0);
  predictor.command_sent(0, 1.0, 0.001);
  predictor.command_sent(1, 0.8, 0.006);
  predictor.command_played(0, 0.001, 1.0);
  predictor.command_played(1, 0.006, 0.3);
  predictor.command_played(2, 0.011, -0.2);
  predictor.command_played(3, 0.016, std::nan(""));  // a report that is no command: ignored
  PredictedState expected{0.0, 0.0, 0.0};
  advance_model(model, expected, 0.001, 0.0);
  advance_model(model, expected, 0.005, 1.0);
  advance_model(model, expected, 0.005, 0.3);
  advance_model(model, expected, 0.009, -0.2);
  EXPECT_NEAR(predictor.predict_position(0.020), expected.position_m, 1e-15);
  // run_on: the same model on from a predicted state, under a command saturated at the limit.
  AxisStatePredictor limited(model, 0.005, 0.5);
  PredictedState from = expected;
  advance_model(model, expected, 0.004, 0.5);
  EXPECT_NEAR(limited.run_on(from, 0.004, 2.0).position_m, expected.position_m, 1e-15);
  EXPECT_EQ(limited.run_on(from, 0.0, 2.0).position_m, from.position_m);
}

TEST(AxisStatePredictor, ACommandBeyondTheLimitActsAsTheLimit) {
  const PredictionModel model{.damping_per_s = 0.0, .input_gain = 10.0, .observer_bandwidth_rad_s = 100.0};
  AxisStatePredictor limited(model, 0.005, 1.0), free(model, 0.005);
  for (auto* predictor : {&limited, &free}) {
    predictor->reset(0.0);
    predictor->measured(0, 0.0, 0.0);
  }
  limited.command_sent(0, 7.0, 0.0);
  free.command_sent(0, 1.0, 0.0);
  EXPECT_EQ(limited.predict_position(0.02), free.predict_position(0.02));
  limited.command_sent(1, std::nan(""), 0.005);  // a non-finite command acts as 0 (the axis trips on it)
  EXPECT_TRUE(std::isfinite(limited.predict_position(0.02)));
}

TEST(AxisStatePredictor, OlderSamplesThanTheNewestAreIgnored) {
  AxisStatePredictor predictor(PredictionModel{.damping_per_s = 0.0, .input_gain = 20.0, .observer_bandwidth_rad_s = 100.0}, 0.005);
  predictor.reset(0.0);
  predictor.measured(3, 0.015, 0.002);
  predictor.measured(2, 0.010, 0.5);  // reordered on the uplink: older than the newest
  EXPECT_EQ(predictor.newest_sample_time_s(), 0.015);
  EXPECT_EQ(predictor.predict_position(0.015), 0.002);
}

TEST(AxisStatePredictor, MemoryStaysBoundedWithoutFeedback) {
  AxisStatePredictor predictor(PredictionModel{.damping_per_s = 0.0, .input_gain = 20.0, .observer_bandwidth_rad_s = 100.0}, 0.005);
  predictor.reset(0.0);
  predictor.measured(0, 0.0, 0.0);
  for (std::uint64_t k = 1; k < 3 * AxisStatePredictor::kMaxPendingCommands; ++k) {
    predictor.command_sent(k, 0.0, static_cast<double>(k) * 0.005);
    ASSERT_LE(predictor.pending_commands(), AxisStatePredictor::kMaxPendingCommands);
  }
  EXPECT_EQ(predictor.pending_commands(), AxisStatePredictor::kMaxPendingCommands);
  EXPECT_EQ(predictor.predict_position(100.0), 0.0);  // every command 0, the axis at rest at 0
}

TEST(AxisStatePredictor, RefusesAModelItCannotObserve) {
  EXPECT_THROW(AxisStatePredictor(PredictionModel{.damping_per_s = 0.0, .input_gain = 20.0, .observer_bandwidth_rad_s = -1.0}, 0.005), std::invalid_argument);
  EXPECT_THROW(AxisStatePredictor(PredictionModel{.damping_per_s = std::nan(""), .input_gain = 20.0, .observer_bandwidth_rad_s = 100.0}, 0.005), std::invalid_argument);
  EXPECT_THROW(AxisStatePredictor(PredictionModel{.damping_per_s = 0.0, .input_gain = 20.0, .observer_bandwidth_rad_s = 100.0}, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::control
