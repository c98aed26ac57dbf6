// The seed001 test FMU against the built-in SecondOrderAxis with the same parameters: the FMU
// plant must give the built-in plant's numbers (a linear axis within 1e-9, paper 001's axis with
// friction on paper 001's circle within 1e-6, relative to each signal's peak over the run).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <random>
#include <string>

#include "plant/plant_catalog.hpp"
#include "plant/second_order_axis.hpp"
#include "test_fmu.hpp"

namespace netmc::plant::fmu {
namespace {

using test::fmu_axis;

// Largest difference between two signals, relative to the reference's peak over the run.
class Agreement {
 public:
  void add(double fmu, double reference) {
    difference_ = std::max(difference_, std::abs(fmu - reference));
    peak_ = std::max(peak_, std::abs(reference));
  }
  double relative() const { return peak_ > 0.0 ? difference_ / peak_ : difference_; }

 private:
  double difference_ = 0.0, peak_ = 0.0;
};

std::vector<std::pair<std::string, double>> fmu_parameters(const SecondOrderAxisParameters& p) {
  return {{"a1", p.a1},
          {"a2", p.a2},
          {"b", p.b},
          {"coulomb", p.coulomb_acceleration},
          {"coulomb_velocity_scale", p.coulomb_velocity_scale},
          {"max_substep", p.max_substep_s}};
}

SecondOrderAxisParameters linear(double a2, double b) {
  SecondOrderAxisParameters p;
  p.a1 = 0.0;
  p.a2 = a2;
  p.b = b;
  p.coulomb_acceleration = 0.0;
  return p;
}

// A held-input sequence of uneven durations, some longer than the FMU's 1 ms step.
void run_linear(const SecondOrderAxisParameters& p, const std::string& label) {
  SecondOrderAxis reference(p);
  auto plant = fmu_axis(NETMC_TEST_FMU_SEED001_AXIS, ":velocity=v", fmu_parameters(p));
  reference.reset(0.002, -0.01);
  plant->reset(0.002, -0.01);
  const double durations[] = {1e-3, 0.5e-3, 2.5e-3, 0.3e-3, 4.7e-3, 1e-3, 10e-3};
  Agreement position, velocity;
  for (int k = 0; k < 2000; ++k) {
    const double duration = durations[k % 7];
    const double input = 0.8 * std::sin(0.37 * k) + 0.1 * std::cos(0.05 * k);
    reference.advance(duration, input);
    plant->advance(duration, input);
    position.add(plant->position(), reference.position());
    velocity.add(plant->velocity(), reference.velocity());
    ASSERT_NEAR(plant->time(), reference.time(), 1e-12);
  }
  std::cout << "[ figures  ] linear " << label << ": max |dx| / max |x| = " << position.relative()
            << ", max |dv| / max |v| = " << velocity.relative() << "\n";
  EXPECT_LT(position.relative(), 1e-9);
  EXPECT_LT(velocity.relative(), 1e-9);
}

TEST(FmuAgreement, LinearAxisMatchesTheExactBuiltInWithin1e9) {
  run_linear(linear(-20.0, 20.0), "X (a2 -20, b 20)");
  run_linear(linear(-10.0, 10.0), "Y (a2 -10, b 10)");
}

// Paper 001's circle (server/job/presets/presets_paper001.cpp, seed001_job: r = 10 mm about (50, 50) mm, period 8 s,
// h = 5 ms, downlink delay tau ~ U(0.3, 0.8) ms): each period the old command holds for tau and
// the new one for h - tau. The command is a PD law with feedforward on the built-in axis's state,
// applied to both plants alike, so differences do not feed back.
struct CircleResult {
  Agreement position, velocity;
};

CircleResult run_circle(std::size_t axis, const std::string& options) {
  const SecondOrderAxisParameters p = seed001_axis_parameters(axis);
  SecondOrderAxis reference(p);
  auto plant = fmu_axis(NETMC_TEST_FMU_SEED001_AXIS, options, fmu_parameters(p));
  constexpr double kRadius = 0.010, kCentre = 0.050, kPeriod = 8.0, kSample = 0.005;
  constexpr double kOmega = 2.0 * std::numbers::pi / kPeriod;
  constexpr double kKp = 400.0, kKd = 40.0;  // 1/s^2, 1/s
  const auto r = [&](double t, int derivative) {
    const double phase = kOmega * t + (axis == 0 ? 0.0 : -std::numbers::pi / 2.0);
    const double scale = std::pow(kOmega, derivative);
    switch (derivative) {
      case 0: return kCentre + kRadius * std::cos(phase);
      case 1: return -kRadius * scale * std::sin(phase);
      default: return -kRadius * scale * std::cos(phase);
    }
  };
  const double start = r(0.0, 0);
  reference.reset(start, 0.0);
  plant->reset(start, 0.0);
  std::mt19937_64 random(1);
  std::uniform_real_distribution<double> delay(0.3e-3, 0.8e-3);
  CircleResult result;
  double held = 0.0;
  for (int k = 0; k < static_cast<int>(kPeriod / kSample); ++k) {
    const double t = k * kSample;
    const double command = (r(t, 2) - p.a2 * r(t, 1) + kKp * (r(t, 0) - reference.position()) +
                            kKd * (r(t, 1) - reference.velocity())) /
                           p.b;
    const double tau = delay(random);
    for (const auto& [duration, input] : {std::pair{tau, held}, std::pair{kSample - tau, command}}) {
      reference.advance(duration, input);
      plant->advance(duration, input);
      result.position.add(plant->position(), reference.position());
      result.velocity.add(plant->velocity(), reference.velocity());
    }
    held = command;
  }
  return result;
}

TEST(FmuAgreement, Paper001AxisWithFrictionOnTheCircleWithin1e6) {
  for (std::size_t axis : {0u, 1u}) {
    for (const char* options : {":velocity=v", ":velocity=v,step=0.25ms"}) {
      const CircleResult result = run_circle(axis, options);
      std::cout << "[ figures  ] circle axis " << (axis == 0 ? "X" : "Y") << " options '" << options
                << "': max |dx| / max |x| = " << result.position.relative()
                << ", max |dv| / max |v| = " << result.velocity.relative() << "\n";
      EXPECT_LT(result.position.relative(), 1e-6);
      EXPECT_LT(result.velocity.relative(), 1e-6);
    }
  }
}

}  // namespace
}  // namespace netmc::plant::fmu
