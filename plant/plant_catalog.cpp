#include "plant/plant_catalog.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "plant/ball_screw_drive.hpp"
#include "plant/dead_zone_input.hpp"
#include "plant/flexible_linear_motor_axis.hpp"
#include "plant/linear_motor_axis.hpp"
#include "plant/resonant_stage_axis.hpp"

// Parameter choices (SI inside; the sources by the short names of docs/references.md):
//
// seed001 -- paper 001, eq. 3. The paper gives no plant numbers; netmc's assumed [A]
//   default is a servo in speed mode, in mm: X a1=0, a2=-20, b=20, d=-50 tanh(x'/0.05) mm/s^2;
//   Y a1=0, a2=-10, b=10, d=-70 tanh(y'/0.05) mm/s^2. In metres the friction becomes
//   0.050 / 0.070 m/s^2 with a velocity scale of 5e-5 m/s; a1, a2, b are unit-free in length
//   (b multiplies the command, whose unit the paper leaves open).
//   Calibrated here (docs/reproductions/paper-001.md, "Plant for paper 001"): velocity scale 1 mm/s and levels 60 / 85
//   mm/s^2 give ADRC-only e_max = 0.083 mm (paper: 0.0811 mm). With the first assumed 0.05 mm/s the
//   friction is almost a step at each velocity reversal; the paper's PD-ILC then stalls at
//   e_max/ADRC = 0.47 after 11 iterations and drifts upwards.
//   Sub-step 1 ms: the stiffest term, the friction slope c/scale = 85 1/s (Y), gives
//   |lambda h| = 0.085; with fifth-order Taylor steps (coulomb_taylor_step.hpp) the study's
//   metrics agree with RK4 at 10 us sub-steps to 7e-9 relative (docs/benchmarks.md).
//
// ballscrew -- paper 002, eq. 1 (section 2) with section 6's parameters, both axes: J = 0.8e-3 kg m^2,
//   B = 0.255 N m s/rad, Ka = 3.2 A/V, Kt = 0.9 N m/A, rg = 5 mm/rad = 0.005 m/rad, giving
//   y'' = -318.75 y' + 18 (u + d) m/s^2 and 56.47 mm/s per volt (derived from eq. 1).
//
// linmotor -- paper 000 (thesis), eq. 2-43 with appendix A nominals (A.8/A.9) in volts:
//   X: M = 0.12 V/(m/s^2), B = 0.3 V/(m/s), A = 0.1 V;
//   Y: M = 0.55 (the Set1 value of sections 3.5.3 and 4.4.2, rather than the 0.5 nominal of A.9),
//      B = 0.4, A = 0.15 V.
//   Cogging, eq. 4-2/4-23 with the measured pitch P = 50 mm, X harmonics 1, 2, 3 and Y harmonics
//   1, 6, 12; the amplitudes are only in Figs. 4-3 and 4-4, so netmc assumes [A]:
//   X (S, C) = (0.05, 0.03), (0.02, -0.01), (0.01, 0.01) V;
//   Y (S, C) = (0.04, -0.02), (0.03, 0.02), (0.015, -0.01) V.
//   Stribeck extra friction is left at 0: eq. A.3 gives its form, the thesis no level.
//   Friction smoothing 1e-4 m/s (the thesis' S_f = 2/pi atan(9000 v) has a similar width);
//   sub-step 2e-5 s keeps RK4 stable on the friction slope A/(M v_s) ~ 8300 1/s (X).
//
// linmotor-flex -- linmotor with appendix A's imperfections (FlexibleLinearMotorAxis; appendix
//   A.2): the rigid nominals, cogging and tanh smoothing above, plus
//   from appendix A: a drive current loop of 1.5 kHz bandwidth; one flexible mode per axis between
//     the motor and the encoder's carriage, its frequency inside A's ranges (X 100-200 Hz, Y 40-80
//     Hz); Stribeck friction per A.3 (xi = 2).
//   fitted to Table 2-2 case C by bench/linmotor_flex_calibration.sh (a grid over the modes'
//     frequencies and damping ratios and the Stribeck level; see the script for the choice):
//     X 150 Hz, Y 60 Hz (the middle of A's ranges), damping ratio 0.45 on both, Stribeck extra
//     0.2 V. With the encoder on the carriage the mode is non-collocated: at zeta ~ 0.35 the
//     thesis gains (K_s = 100, Lambda = 100 normal to the contour) reach their stability edge,
//     above it the contour error is nearly the rigid model's and the Stribeck level sets the RMS
//     (GTCF 2.23 um, thesis 2.20). No point of the search makes GTCF beat LTCF as on the real
//     stage (GTCF / LTCF 0.95-1.0 against the thesis's 0.39).
//   assumed [A]: the carriage carries 30 % of M (it does not change the carriage's response to
//     the drive force, only where friction and cogging act: on the motor side); Stribeck
//     velocity 0.01 m/s (the thesis gives none).
//   The computation delay is not part of the plant: it is the job's compute_delay_s (tau_cc), left
//   at the presets' 0 (the dSPACE board computes within its 0.2 ms period, whose hold the runner
//   already applies).
//   Sub-step 2e-5 s: the fastest poles are the current loop, 2 pi 1500 = 9.4e3 1/s (h lambda =
//   0.19), and the smoothed-friction slope on the motor side, (A + Stribeck) / (M_m v_smooth)
//   ~ 3.6e4 1/s for X (h lambda = 0.71); a 200 Hz mode would be 1.3e3 rad/s. All inside RK4's
//   stability bound 2.8; halving the sub-step moves the case C metrics by at most 0.02 um.
//
// stage004 -- paper 004, eq. 1 with Tables 1 (X) and 2 (Y):
//   X: m = 24 kg; (K, x, f) = (0.013, 0.040, 150 Hz), (0.0023, 0.018, 292 Hz), (0.0018, 0.027, 510
//   Hz); Y: m = 30 kg; (0.018, 0.0432, 182 Hz), (0.0021, 0.0531, 302 Hz). Sub-step 1e-5 s (100 kHz,
//   netmc's choice [A]); with a constant force the modes are exact anyway.
//
// hiwin -- paper 000 (thesis) ch. 5, the Hiwin single-axis linear-motor stage, eq. 5-49 with the
//   Exp I dead zone 5-51: x'' = E w - B x' - A S_f(x'), w = D(v), identified B = 4.3 1/s,
//   A = 0.9 m/s^2 (printed "/s"; it multiplies a unit-free S_f), E = 3.6 m/s^2/V, f_N = 0;
//   D: right 0.9 (v - 1.2), left 1.0 (v + 1) (volts in, volts out). Exp II's symmetric dead zone
//   5-54 is dead_zone_left_slope = 0.9.
//   S_f: chapter 5 and appendix A give no form; chapter 3's is 2/pi atan(9000 v). The plant uses
//   SecondOrderAxis's tanh(v / 1.745e-4 m/s), the same slope at v = 0 (2/pi 9000 = 1/1.745e-4).
//   A disturbance (V) enters at the motor, after the dead zone: E times it as an acceleration.
//   Sub-step 5e-5 s: the friction slope A / 1.745e-4 = 5.2e3 1/s gives h lambda = 0.26.
//   A single-axis stage: a second or third axis, when asked for, is a copy.
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

// Fitted to Table 2-2 case C (see above), except the assumed carriage share.
constexpr double kFlexLoadFraction = 0.3;
constexpr double kFlexModeDampingX = 0.45, kFlexModeDampingY = 0.45;
constexpr double kFlexModeFrequencyXHz = 150.0, kFlexModeFrequencyYHz = 60.0;  // A: 100-200, 40-80
constexpr double kFlexStribeckExtraV = 0.2;

FlexibleLinearMotorParameters flexible_linear_motor_axis_parameters(std::size_t axis) {
  FlexibleLinearMotorParameters p;
  p.motor = linear_motor_axis_parameters(axis);
  p.motor.stribeck_extra = kFlexStribeckExtraV;
  p.motor.stribeck_velocity = 0.01;
  p.load_fraction = kFlexLoadFraction;
  p.mode_damping_ratio = axis == 0 ? kFlexModeDampingX : kFlexModeDampingY;
  p.mode_frequency_hz = axis == 0 ? kFlexModeFrequencyXHz : kFlexModeFrequencyYHz;
  p.current_loop_hz = 1500.0;  // thesis A: about 1.5 kHz
  p.max_substep_s = 2e-5;
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

// Thesis eq. 5-49 / 5-51 (see above); the dead zone in volts, E applied behind it.
struct HiwinParameters {
  double viscous = 4.3;                  // B (1/s)
  double coulomb = 0.9;                  // A (m/s^2)
  double gain = 3.6;                     // E (m/s^2 per V)
  double friction_velocity_scale = 1.745e-4;  // m/s, tanh width of S_f
  DeadZoneParameters dead_zone{1.2, -1.0, 0.9, 1.0};
  Disturbance disturbance;               // V, at the motor input
  double max_substep_s = 5e-5;
};

Disturbance scaled(Disturbance d, double factor) {
  d.constant *= factor;
  d.sine_amplitude *= factor;
  d.step_amplitude *= factor;
  d.noise.stddev *= factor;
  return d;
}

std::unique_ptr<AxisPlant> make_hiwin_axis(const HiwinParameters& p) {
  SecondOrderAxisParameters axis;
  axis.a1 = 0.0;
  axis.a2 = -p.viscous;
  axis.b = p.gain;
  axis.coulomb_acceleration = p.coulomb;
  axis.coulomb_velocity_scale = p.friction_velocity_scale;
  axis.disturbance = scaled(p.disturbance, p.gain);  // V -> m/s^2
  axis.max_substep_s = p.max_substep_s;
  return std::make_unique<DeadZoneInput>(p.dead_zone, std::make_unique<SecondOrderAxis>(axis));
}

// One overridable parameter of a plant's parameter struct P.
template <class P>
struct Setting {
  std::string key;
  std::string description;
  std::function<void(P&, double)> apply;
};

void require_non_negative_value(const std::string& key, double value) {
  if (!(value >= 0.0)) {
    throw std::invalid_argument("plant: " + key + " must be >= 0 (got " + std::to_string(value) + ")");
  }
}

std::vector<Setting<SecondOrderAxisParameters>> seed001_settings() {
  using P = SecondOrderAxisParameters;
  return {
      {"a1", "position coefficient a1 (1/s^2); X 0, Y 0", [](P& p, double v) { p.a1 = v; }},
      {"a2", "velocity coefficient a2 (1/s); X -20, Y -10", [](P& p, double v) { p.a2 = v; }},
      {"b", "input gain b ((m/s^2) per input unit); X 20, Y 10", [](P& p, double v) { p.b = v; }},
      {"coulomb_m_s2", "Coulomb friction level (m/s^2); X 0.060, Y 0.085",
       [](P& p, double v) { p.coulomb_acceleration = v; }},
      {"coulomb_velocity_scale_m_s", "tanh width of the friction sign (m/s); 1e-3",
       [](P& p, double v) { p.coulomb_velocity_scale = v; }},
  };
}

std::vector<Setting<BallScrewParameters>> ballscrew_settings() {
  using P = BallScrewParameters;
  return {
      {"inertia_kg_m2", "J, reflected inertia (kg m^2); 0.8e-3", [](P& p, double v) { p.inertia = v; }},
      {"damping_n_m_s_rad", "B, viscous damping (N m s/rad); 0.255", [](P& p, double v) { p.damping = v; }},
      {"amplifier_gain_a_v", "Ka (A/V); 3.2", [](P& p, double v) { p.amplifier_gain = v; }},
      {"torque_constant_n_m_a", "Kt (N m/A); 0.9", [](P& p, double v) { p.torque_constant = v; }},
      {"lead_m_rad", "rg, screw lead (m/rad); 0.005", [](P& p, double v) { p.lead_m_per_rad = v; }},
      // paper 002's load (section 6.3), as netmc assumes [A]: a payload m on the table adds m rg^2 to J
      // (3 kg: 0.875e-3 kg m^2)
      {"load_kg", "payload on the table (kg), adds load * rg^2 to J; 0",
       [](P& p, double v) {
         require_non_negative_value("load_kg", v);
         p.inertia += v * p.lead_m_per_rad * p.lead_m_per_rad;
       }},
  };
}

std::vector<Setting<LinearMotorParameters>> linmotor_settings() {
  using P = LinearMotorParameters;
  return {
      {"mass_v_s2_m", "M, moving mass (V/(m/s^2)); X 0.12, Y 0.55", [](P& p, double v) { p.mass = v; }},
      {"load_v_s2_m", "payload mass added to M (V/(m/s^2)); 0",
       [](P& p, double v) {
         require_non_negative_value("load_v_s2_m", v);
         p.mass += v;
       }},
      {"damping_v_s_m", "B, viscous friction (V/(m/s)); X 0.3, Y 0.4", [](P& p, double v) { p.damping = v; }},
      {"coulomb_v", "A, Coulomb friction (V); X 0.1, Y 0.15", [](P& p, double v) { p.coulomb = v; }},
      {"stribeck_extra_v", "static minus Coulomb friction (V); 0", [](P& p, double v) { p.stribeck_extra = v; }},
      {"stribeck_velocity_m_s", "Stribeck velocity (m/s); 0.01", [](P& p, double v) { p.stribeck_velocity = v; }},
      {"cogging_scale", "factor on every cogging amplitude; 1",
       [](P& p, double v) {
         for (auto& harmonic : p.cogging) {
           harmonic.sine *= v;
           harmonic.cosine *= v;
         }
       }},
  };
}

std::vector<Setting<FlexibleLinearMotorParameters>> linmotor_flex_settings() {
  using P = FlexibleLinearMotorParameters;
  std::vector<Setting<P>> out;
  // linmotor's keys act on the rigid part; a payload rides on the carriage.
  for (auto& rigid : linmotor_settings()) {
    if (rigid.key == "load_v_s2_m") continue;
    const std::string description =
        rigid.key == "stribeck_extra_v" ? "static minus Coulomb friction, thesis A.3 (V); 0.2" : rigid.description;
    out.push_back({rigid.key, description, [apply = rigid.apply](P& p, double v) { apply(p.motor, v); }});
  }
  out.push_back({"load_v_s2_m", "payload mass added to the carriage (V/(m/s^2)); 0", [](P& p, double v) {
                   require_non_negative_value("load_v_s2_m", v);
                   const double carriage = p.load_fraction * p.motor.mass + v;
                   p.motor.mass += v;
                   p.load_fraction = carriage / p.motor.mass;
                 }});
  out.push_back({"load_fraction", "carriage's share of M (encoder side of the mode), in (0, 1); 0.3",
                 [](P& p, double v) { p.load_fraction = v; }});
  out.push_back({"mode_frequency_hz", "flexible mode between motor and carriage (Hz); X 150, Y 60",
                 [](P& p, double v) { p.mode_frequency_hz = v; }});
  out.push_back({"mode_damping", "damping ratio of the flexible mode; 0.45",
                 [](P& p, double v) { p.mode_damping_ratio = v; }});
  out.push_back({"current_loop_hz", "drive current-loop bandwidth (Hz); 1500",
                 [](P& p, double v) { p.current_loop_hz = v; }});
  out.push_back({"max_substep_s", "RK4 sub-step bound (s); 2e-5", [](P& p, double v) { p.max_substep_s = v; }});
  return out;
}

std::vector<Setting<ResonantStageParameters>> stage004_settings() {
  using P = ResonantStageParameters;
  std::vector<Setting<P>> out = {
      {"mass_kg", "m, moving mass (kg); X 24, Y 30", [](P& p, double v) { p.mass = v; }},
      {"load_kg", "payload added to m (kg); 0",
       [](P& p, double v) {
         require_non_negative_value("load_kg", v);
         p.mass += v;
       }},
  };
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string n = std::to_string(i + 1);
    auto mode = [i, n](P& p) -> ResonanceMode& {
      if (i >= p.modes.size()) {
        throw std::invalid_argument("plant: this axis has " + std::to_string(p.modes.size()) +
                                    " resonances, not " + n);
      }
      return p.modes[i];
    };
    out.push_back({"mode" + n + "_gain", "K_" + n + " of resonance " + n + " (m/(N s^2))",
                   [mode](P& p, double v) { mode(p).gain = v; }});
    out.push_back({"mode" + n + "_damping", "x_" + n + ", damping ratio of resonance " + n,
                   [mode](P& p, double v) { mode(p).damping_ratio = v; }});
    out.push_back({"mode" + n + "_frequency_hz", "f_" + n + " (Hz)",
                   [mode](P& p, double v) { mode(p).frequency_hz = v; }});
  }
  return out;
}

// The input dead zone of thesis eq. 5-2, in front of an axis: hiwin's is part of its model; every
// other plant takes one per axis through the same keys (thesis section 5.5: a contouring stage
// whose drives have dead zones), none by default.
std::vector<Setting<DeadZoneParameters>> dead_zone_settings(const DeadZoneParameters& nominal, const std::string& unit) {
  using P = DeadZoneParameters;
  const auto number = [](double v) {
    std::ostringstream text;  // shortest form: 1.2, -1, 0.9
    text << v;
    return text.str();
  };
  return {
      {"dead_zone_right_v", "b_r, right break point of the input dead zone (" + unit + "), >= 0; " + number(nominal.right_break_v),
       [](P& p, double v) { p.right_break_v = v; }},
      {"dead_zone_left_v", "b_l, left break point of the input dead zone (" + unit + "), <= 0; " + number(nominal.left_break_v),
       [](P& p, double v) { p.left_break_v = v; }},
      {"dead_zone_right_slope", "m_r, right slope of the dead zone (" + unit + "/" + unit + "), > 0; " + number(nominal.right_slope),
       [](P& p, double v) { p.right_slope = v; }},
      {"dead_zone_left_slope", "m_l, left slope of the dead zone (" + unit + "/" + unit + "), > 0; " + number(nominal.left_slope),
       [](P& p, double v) { p.left_slope = v; }},
  };
}

std::vector<Setting<HiwinParameters>> hiwin_settings() {
  using P = HiwinParameters;
  std::vector<Setting<P>> out = {
      {"viscous_1_s", "B, viscous friction (1/s); 4.3", [](P& p, double v) { p.viscous = v; }},
      {"coulomb_m_s2", "A, Coulomb friction (m/s^2); 0.9", [](P& p, double v) { p.coulomb = v; }},
      {"gain_m_s2_v", "E, motor input gain ((m/s^2)/V); 3.6", [](P& p, double v) { p.gain = v; }},
      {"friction_velocity_scale_m_s", "tanh width of S_f (m/s); 1.745e-4",
       [](P& p, double v) { p.friction_velocity_scale = v; }},
      {"max_substep_s", "RK4 sub-step bound (s); 5e-5", [](P& p, double v) { p.max_substep_s = v; }},
  };
  // Exp I's dead zone (5-51); Exp II's symmetric one (5-54) is dead_zone_left_slope = 0.9.
  for (auto& dead_zone : dead_zone_settings(HiwinParameters{}.dead_zone, "V")) {
    out.push_back({dead_zone.key, dead_zone.description,
                   [apply = dead_zone.apply](P& p, double v) { apply(p.dead_zone, v); }});
  }
  return out;
}

template <class P>
std::vector<PlantParameter> describe_settings(const std::vector<Setting<P>>& settings) {
  std::vector<PlantParameter> out;
  for (const auto& s : settings) out.push_back({s.key, s.description});
  return out;
}

// The axis's nominal parameters with the job's overrides applied in order.
template <class P>
P with_overrides(P p, const std::vector<Setting<P>>& settings, const AxisOverrides* overrides,
                 std::string_view plant_name) {
  if (!overrides) return p;
  for (const auto& [key, value] : overrides->parameters) {
    if (!std::isfinite(value)) {
      throw std::invalid_argument("plant: " + key + " must be a finite number (got " + std::to_string(value) + ")");
    }
    const auto it = std::find_if(settings.begin(), settings.end(), [&](const auto& s) { return s.key == key; });
    if (it == settings.end()) {
      std::string keys;
      for (const auto& s : settings) keys += (keys.empty() ? "" : ", ") + s.key;
      throw std::invalid_argument("plant: " + std::string(plant_name) + " has no parameter '" + key.substr(0, 64) +
                                  "' (expected one of: " + keys + ")");
    }
    it->apply(p, value);
  }
  p.disturbance = overrides->disturbance;
  return p;
}

const char* const kNames[] = {"seed001", "ballscrew", "linmotor", "stage004", "linmotor-flex", "hiwin"};
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

bool is_file_plant(std::string_view name) {
  return name.substr(0, 4) == "fmu:" || name.substr(0, 7) == "plugin:";
}

std::vector<std::string> plant_names() { return {std::begin(kNames), std::end(kNames)}; }

std::vector<PlantParameter> plant_parameters(std::string_view name) {
  if (name == "hiwin") return describe_settings(hiwin_settings());
  std::vector<PlantParameter> out;
  if (name == "seed001") {
    out = describe_settings(seed001_settings());
  } else if (name == "ballscrew") {
    out = describe_settings(ballscrew_settings());
  } else if (name == "linmotor") {
    out = describe_settings(linmotor_settings());
  } else if (name == "stage004") {
    out = describe_settings(stage004_settings());
  } else if (name == "linmotor-flex") {
    out = describe_settings(linmotor_flex_settings());
  } else {
    throw std::invalid_argument("plant: unknown name '" + std::string(name) + "' (expected one of: " + expected_names() + ")");
  }
  for (const auto& p : describe_settings(dead_zone_settings({}, plant_input_unit(name)))) out.push_back(p);
  return out;
}

// Travel and rated input (see plant_rating in the header). Every studied contour stays inside the
// travel; the rated input is where a source names the amplifier's range, else an assumption [A]
// with room above the studies' commands (largest |U| of each preset's runs in brackets):
//   seed001   [A] paper 001 gives no machine: travel -0.1..0.2 m around its contours (30-80 mm);
//             rated 1 (the speed-mode servo's command, 1 m/s at steady state) [0.03; 12 in
//             seed001-long-delay's unstable PID-CCC run].
//   ballscrew paper 002: stroke 150 mm per axis, 0..0.15 m; [A] +-10 V, the amplifiers' analog
//             input range (Ka in A/V) [the paper's own runs diverge past it].
//   linmotor, linmotor-flex  thesis appendix A: 500 x 500 mm travel, -0.25..0.25 m; +-10 V, the
//             DS1103 outputs to the amplifiers (force linear to about 8 V) [chapter 2-4 runs
//             reach 30-50 V in their first cycles: the thesis simulates them unsaturated].
//   hiwin     [A] the thesis gives no travel: -0.05..0.45 m around chapter 5's 0-0.4 m; +-10 V [3].
//   stage004  [A] paper 004 gives neither: travel -0.2..0.2 m around its -64..100 mm contours;
//             rated 100 N [50].
PlantRating plant_rating(std::string_view name) {
  if (name == "seed001") return {-0.1, 0.2, 1.0};
  if (name == "ballscrew") return {0.0, 0.15, 10.0};
  if (name == "linmotor" || name == "linmotor-flex") return {-0.25, 0.25, 10.0};
  if (name == "hiwin") return {-0.05, 0.45, 10.0};
  if (name == "stage004") return {-0.2, 0.2, 100.0};
  throw std::invalid_argument("plant: unknown name '" + std::string(name) + "' (expected one of: " + expected_names() +
                              ")");
}

std::string plant_input_unit(std::string_view name) {
  if (name == "seed001") return "m/s^2";
  if (name == "stage004") return "N";
  if (std::find(std::begin(kNames), std::end(kNames), name) == std::end(kNames)) {
    throw std::invalid_argument("plant: unknown name '" + std::string(name) + "' (expected one of: " + expected_names() + ")");
  }
  return "V";
}

AxisSet make_plant_set(std::string_view name, std::size_t axis_count, const std::vector<AxisOverrides>& overrides) {
  std::string title;
  if (name == "seed001") {
    title = "seed001: paper 001 eq. 3 servo axes (netmc's assumed parameters [A])";
  } else if (name == "ballscrew") {
    title = "ballscrew: paper 002 eq. 1 ball-screw drives (nominal J, B, Ka, Kt, rg)";
  } else if (name == "linmotor") {
    title = "linmotor: paper 000 linear motors (X/Y nominals, friction, cogging [A])";
  } else if (name == "linmotor-flex") {
    title = "linmotor-flex: paper 000 linear motors with appendix A's flexible mode, current loop and Stribeck friction";
  } else if (name == "stage004") {
    title = "stage004: paper 004 eq. 1 H-bridge stage with resonances (Tables 1/2)";
  } else if (name == "hiwin") {
    title = "hiwin: paper 000 ch. 5 single-axis linear motor with an input dead zone (eq. 5-49, 5-51)";
  } else {
    throw std::invalid_argument("plant: unknown name '" + std::string(name) +
                                "' (expected one of: " + expected_names() + ")");
  }
  if (axis_count < 1 || axis_count > 3) {
    throw std::invalid_argument("plant: axis_count must be 1, 2 or 3 (got " +
                                std::to_string(axis_count) + ")");
  }
  if (overrides.size() > axis_count) {
    throw std::invalid_argument("plant: overrides for " + std::to_string(overrides.size()) + " axes, the set has " +
                                std::to_string(axis_count));
  }
  AxisSet set;
  set.description = title;
  for (std::size_t axis = 0; axis < axis_count; ++axis) {
    // A dead zone in front of the axis (every plant but hiwin, whose model holds its own): its
    // keys apply to a DeadZoneInput around the plant, the rest to the plant.
    AxisOverrides plant_changes;
    DeadZoneParameters dead_zone;
    bool has_dead_zone = false;
    if (axis < overrides.size()) {
      plant_changes.disturbance = overrides[axis].disturbance;
      const auto keys = dead_zone_settings({}, "");
      for (const auto& [key, value] : overrides[axis].parameters) {
        const auto it = std::find_if(keys.begin(), keys.end(), [&](const auto& k) { return k.key == key; });
        if (name == "hiwin" || it == keys.end()) {
          plant_changes.parameters.emplace_back(key, value);
        } else if (!std::isfinite(value)) {
          throw std::invalid_argument("plant: " + key + " must be a finite number (got " + std::to_string(value) + ")");
        } else {
          it->apply(dead_zone, value);
          has_dead_zone = true;
        }
      }
    }
    const AxisOverrides* changes = axis < overrides.size() ? &plant_changes : nullptr;
    std::unique_ptr<AxisPlant> plant;
    if (name == "seed001") {
      plant = std::make_unique<SecondOrderAxis>(with_overrides(seed001_axis_parameters(axis), seed001_settings(), changes, name));
    } else if (name == "ballscrew") {
      plant = std::make_unique<BallScrewDrive>(with_overrides(ball_screw_axis_parameters(), ballscrew_settings(), changes, name));
    } else if (name == "linmotor") {
      plant = std::make_unique<LinearMotorAxis>(
          with_overrides(linear_motor_axis_parameters(axis), linmotor_settings(), changes, name));
    } else if (name == "linmotor-flex") {
      plant = std::make_unique<FlexibleLinearMotorAxis>(with_overrides(
          flexible_linear_motor_axis_parameters(axis), linmotor_flex_settings(), changes, name));
    } else if (name == "hiwin") {
      plant = make_hiwin_axis(with_overrides(HiwinParameters{}, hiwin_settings(), changes, name));
    } else {
      plant = std::make_unique<ResonantStageAxis>(
          with_overrides(stage004_axis_parameters(axis), stage004_settings(), changes, name));
    }
    if (has_dead_zone) {
      try {
        plant = std::make_unique<DeadZoneInput>(dead_zone, std::move(plant));
      } catch (const std::invalid_argument& error) {
        throw std::invalid_argument(std::string("plant: dead zone: ") + error.what());
      }
    }
    plant->reset(0.0, 0.0);
    set.description += std::string(" | ") + kAxisLabels[axis] + ": " + plant->describe();
    set.axes.push_back(std::move(plant));
  }
  return set;
}

}  // namespace netmc::plant
