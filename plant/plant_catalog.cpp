#include "plant/plant_catalog.hpp"

#include <stdexcept>
#include <string>

#include "plant/ball_screw_drive.hpp"
#include "plant/linear_motor_axis.hpp"
#include "plant/resonant_stage_axis.hpp"

// Parameter choices (SI inside; see /work/shared/design/seeds-digest.md):
//
// seed001 -- paper 001, eq. 3. The paper gives no plant numbers (digest 1.7 [G]); the digest's
//   [A] default is a servo in speed mode, in mm: X a1=0, a2=-20, b=20, d=-50 tanh(x'/0.05) mm/s^2;
//   Y a1=0, a2=-10, b=10, d=-70 tanh(y'/0.05) mm/s^2. In metres the friction becomes
//   0.050 / 0.070 m/s^2 with a velocity scale of 5e-5 m/s; a1, a2, b are unit-free in length
//   (b multiplies the command, whose unit the paper leaves open).
//   Calibrated here (README, "Plant for paper 001"): velocity scale 1 mm/s and levels 60 / 85
//   mm/s^2 give ADRC-only e_max = 0.083 mm (paper: 0.0811 mm). With the digest's 0.05 mm/s the
//   friction is almost a step at each velocity reversal; the paper's PD-ILC then stalls at
//   e_max/ADRC = 0.47 after 11 iterations and drifts upwards.
//   Sub-step 1 ms: the stiffest term, the friction slope c/scale = 85 1/s (Y), gives
//   |lambda h| = 0.085; with fifth-order Taylor steps (coulomb_taylor_step.hpp) the study's
//   metrics agree with RK4 at 10 us sub-steps to 7e-9 relative (README, Performance).
//
// ballscrew -- paper 002, eq. 1 and section 3.1, both axes identical: J = 0.8e-3 kg m^2,
//   B = 0.255 N m s/rad, Ka = 3.2 A/V, Kt = 0.9 N m/A, rg = 5 mm/rad = 0.005 m/rad, giving
//   y'' = -318.75 y' + 18 (u + d) m/s^2 and 56.47 mm/s per volt (digest 3.1 [D]).
//
// linmotor -- paper 000 (thesis), eq. 2-43 with appendix A nominals (A.8/A.9) in volts:
//   X: M = 0.12 V/(m/s^2), B = 0.3 V/(m/s), A = 0.1 V;
//   Y: M = 0.55 (ch. 4 Set1 value, digest 2.12 [G]: use 0.55 rather than the 0.5 nominal),
//      B = 0.4, A = 0.15 V.
//   Cogging, eq. 4-2/4-23 with the measured pitch P = 50 mm, X harmonics 1, 2, 3 and Y harmonics
//   1, 6, 12; the amplitudes are only in figures, so the digest's [A] values (2.12) are used:
//   X (S, C) = (0.05, 0.03), (0.02, -0.01), (0.01, 0.01) V;
//   Y (S, C) = (0.04, -0.02), (0.03, 0.02), (0.015, -0.01) V.
//   Stribeck extra friction is left at 0: the digest suggests it "for realism" but gives no level.
//   Friction smoothing 1e-4 m/s (the thesis' S_f = 2/pi atan(9000 v) has a similar width);
//   sub-step 2e-5 s keeps RK4 stable on the friction slope A/(M v_s) ~ 8300 1/s (X).
//
// stage004 -- paper 004, eq. 1 with Tables 1 (X) and 2 (Y):
//   X: m = 24 kg; (K, x, f) = (0.013, 0.040, 150 Hz), (0.0023, 0.018, 292 Hz), (0.0018, 0.027, 510
//   Hz); Y: m = 30 kg; (0.018, 0.0432, 182 Hz), (0.0021, 0.0531, 302 Hz). Sub-step 1e-5 s (100 kHz,
//   digest 4.6 [A]); with a constant force the modes are exact anyway.
//
// A third axis, when asked for, copies the second axis's parameters.

namespace netmc::plant {
namespace {

BallScrewParameters ball_screw_axis_parameters() { return BallScrewParameters{}; }

LinearMotorParameters linear_motor_axis_parameters(std::size_t axis) {
  LinearMotorParameters p;
  p.cogging_pitch_m = 0.05;
  if (axis == 0) {
    p.mass = 0.12;
    p.damping = 0.3;
    p.coulomb = 0.1;
    p.cogging = {{0.05, 0.03, 1}, {0.02, -0.01, 2}, {0.01, 0.01, 3}};
  } else {
    p.mass = 0.55;
    p.damping = 0.4;
    p.coulomb = 0.15;
    p.cogging = {{0.04, -0.02, 1}, {0.03, 0.02, 6}, {0.015, -0.01, 12}};
  }
  return p;
}

ResonantStageParameters stage004_axis_parameters(std::size_t axis) {
  ResonantStageParameters p;
  if (axis == 0) {
    p.mass = 24.0;
    p.modes = {{0.013, 0.040, 150.0}, {0.0023, 0.018, 292.0}, {0.0018, 0.027, 510.0}};
  } else {
    p.mass = 30.0;
    p.modes = {{0.018, 0.0432, 182.0}, {0.0021, 0.0531, 302.0}};
  }
  return p;
}

const char* const kNames[] = {"seed001", "ballscrew", "linmotor", "stage004"};
const char* const kAxisLabels[] = {"X", "Y", "Z"};

std::string expected_names() {
  std::string out;
  for (const char* n : kNames) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

}  // namespace

SecondOrderAxisParameters seed001_axis_parameters(std::size_t axis) {
  if (axis > 2) {
    throw std::invalid_argument("plant: seed001 axis must be 0, 1 or 2 (got " +
                                std::to_string(axis) + ")");
  }
  SecondOrderAxisParameters p;
  p.a1 = 0.0;
  p.coulomb_velocity_scale = 1e-3;  // 1 mm/s
  p.max_substep_s = 1e-3;  // see above
  if (axis == 0) {
    p.a2 = -20.0;
    p.b = 20.0;
    p.coulomb_acceleration = 0.060;  // 60 mm/s^2
  } else {
    p.a2 = -10.0;
    p.b = 10.0;
    p.coulomb_acceleration = 0.085;  // 85 mm/s^2
  }
  return p;
}

std::vector<std::string> plant_names() { return {std::begin(kNames), std::end(kNames)}; }

AxisSet make_plant_set(std::string_view name, std::size_t axis_count) {
  std::string title;
  if (name == "seed001") {
    title = "seed001: paper 001 eq. 3 servo axes (digest 1.7 [A] defaults)";
  } else if (name == "ballscrew") {
    title = "ballscrew: paper 002 eq. 1 ball-screw drives (nominal J, B, Ka, Kt, rg)";
  } else if (name == "linmotor") {
    title = "linmotor: paper 000 linear motors (X/Y nominals, friction, cogging [A])";
  } else if (name == "stage004") {
    title = "stage004: paper 004 eq. 1 H-bridge stage with resonances (Tables 1/2)";
  } else {
    throw std::invalid_argument("plant: unknown name '" + std::string(name) +
                                "' (expected one of: " + expected_names() + ")");
  }
  if (axis_count < 1 || axis_count > 3) {
    throw std::invalid_argument("plant: axis_count must be 1, 2 or 3 (got " +
                                std::to_string(axis_count) + ")");
  }
  AxisSet set;
  set.description = title;
  for (std::size_t axis = 0; axis < axis_count; ++axis) {
    std::unique_ptr<AxisPlant> plant;
    if (name == "seed001") {
      plant = std::make_unique<SecondOrderAxis>(seed001_axis_parameters(axis));
    } else if (name == "ballscrew") {
      plant = std::make_unique<BallScrewDrive>(ball_screw_axis_parameters());
    } else if (name == "linmotor") {
      plant = std::make_unique<LinearMotorAxis>(linear_motor_axis_parameters(axis));
    } else {
      plant = std::make_unique<ResonantStageAxis>(stage004_axis_parameters(axis));
    }
    plant->reset(0.0, 0.0);
    set.description += std::string(" | ") + kAxisLabels[axis] + ": " + plant->describe();
    set.axes.push_back(std::move(plant));
  }
  return set;
}

}  // namespace netmc::plant
