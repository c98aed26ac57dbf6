#pragma once
// Runs the netmc command line in-process and captures what it prints.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "client/cli_app.hpp"

namespace netmc::cli {

struct NetmcOutcome {
  int exit_code;
  std::string err;
  std::string out;
};

inline NetmcOutcome run_netmc_captured(const std::vector<std::string>& arguments) {
  std::vector<const char*> argv{"netmc"};
  for (const auto& argument : arguments) argv.push_back(argument.c_str());
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();
  const int code = run_netmc(static_cast<int>(argv.size()), argv.data());
  const std::string out = testing::internal::GetCapturedStdout();
  return {code, testing::internal::GetCapturedStderr(), out};
}

}  // namespace netmc::cli
