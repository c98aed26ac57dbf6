#pragma once
// Helpers of the FMU plant tests: one axis of a test FMU, and the message of an expected throw.

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "server/fmu/fmu_axis_plant.hpp"
#include "server/fmu/fmu_plant_set.hpp"

namespace netmc::plant::fmu::test {

// Axis 0 of `fmu` with `options` (":KEY=VALUE,..." or "") and per-axis parameters.
inline std::unique_ptr<AxisPlant> fmu_axis(const std::string& fmu, const std::string& options = "",
                                           std::vector<std::pair<std::string, double>> parameters = {}) {
  AxisOverrides overrides;
  overrides.parameters = std::move(parameters);
  AxisSet set = make_fmu_plant_set(fmu + options, 1, {overrides});
  return std::move(set.axes.at(0));
}

inline FmuAxisPlant& as_fmu(AxisPlant& plant) { return dynamic_cast<FmuAxisPlant&>(plant); }

// what() of the E that `call` throws; a test failure (and "") when it throws nothing.
template <class E>
std::string message_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const E& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected an exception";
  return "";
}

}  // namespace netmc::plant::fmu::test
