#pragma once
// The message build_contour_job refuses a spec with, or "" if it builds: what the builder's and
// the registry's tests compare against.
#include <stdexcept>
#include <string>

#include "server/job/job_builder.hpp"

namespace netmc::job {

inline std::string error_of(const netmc::v1::JobSpec& spec) {
  try {
    build_contour_job(spec);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

}  // namespace netmc::job
