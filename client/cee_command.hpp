#pragma once
// `netmc cee`: compares contour-error estimators (tangent, Newton and Steffensen foot point)
// against the exact contour error on paper 002's circle and heart with a cloud of tracking
// errors: estimation error, iterations and time per estimate.

#include <CLI/CLI.hpp>

#include <functional>

namespace netmc::cli {

std::function<int()> add_cee_command(CLI::App& app);

}  // namespace netmc::cli
