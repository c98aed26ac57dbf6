#pragma once
// The text of `--plant fmu:PATH.fmu[:KEY=VALUE,...]` after "fmu:" (the prefix itself is taken
// too). PATH ends at the first ':' (a path with ':' in it cannot be named) and ends in ".fmu".
// Keys:
//   input=NAME           the Real input variable (causality input), default u
//   output=NAME          the Real position output (causality output, m), default x
//   velocity=NAME        a Real velocity output (m/s); without one velocity() is estimated
//   step=DURATION        the longest fmi2DoStep, e.g. 1ms, 250us, 0.002s; default the FMU's
//                        DefaultExperiment stepSize, else 1 ms
//   position_start=NAME  the variable set to the position on reset(), default x0 if it exists
//   velocity_start=NAME  the variable set to the velocity on reset(), default v0 if it exists
//   [AXIS.]NAME=NUMBER   any other key: a Real parameter of the FMU set before initialisation,
//                        for every axis, or for one axis named by AXIS (0, 1, 2 or x, y, z)
// Parsed strictly and bounded: keys and names of [A-Za-z0-9_.[]] (at most kMaxFmuKeyLength
// characters), numbers finite decimals, no key twice, at most kMaxFmuOptions options. Every
// problem is one std::invalid_argument naming the key. Which variables exist, and which axis a
// qualified key means, is resolved against the FMU's description later (fmu_plant_set.cpp).

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace netmc::plant::fmu {

inline constexpr std::size_t kMaxFmuOptionsText = 8192;
inline constexpr std::size_t kMaxFmuPathLength = 4096;
inline constexpr std::size_t kMaxFmuKeyLength = 128;
inline constexpr std::size_t kMaxFmuOptions = 256;

struct FmuParameterOption {
  std::string key;  // as written, maybe axis-qualified
  double value = 0.0;
};

inline constexpr const char* kDefaultFmuInput = "u";
inline constexpr const char* kDefaultFmuOutput = "x";
inline constexpr const char* kDefaultFmuPositionStart = "x0";
inline constexpr const char* kDefaultFmuVelocityStart = "v0";

struct FmuPlantOptions {
  std::string path;
  std::optional<std::string> input;   // empty: kDefaultFmuInput
  std::optional<std::string> output;  // empty: kDefaultFmuOutput
  std::optional<std::string> velocity;
  std::optional<double> step_s;
  std::optional<std::string> position_start;
  std::optional<std::string> velocity_start;
  std::vector<FmuParameterOption> parameters;  // in the order given
};

FmuPlantOptions parse_fmu_plant_options(std::string_view text);

// "1ms", "250us", "0.002s", "20ns": a positive finite duration in seconds; nullopt otherwise.
std::optional<double> parse_fmu_duration(std::string_view text);

}  // namespace netmc::plant::fmu
