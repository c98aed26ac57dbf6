#pragma once
// A dead zone of thesis eq. 5-2 as a spec gives it (break points and slopes, volts) into the
// estimate an inverse uses; checked against its documented ranges.
#include <string>

#include "control/dead_zone/dead_zone_inverse.hpp"
#include "idl/job.pb.h"

namespace netmc::job {

// Throws std::invalid_argument naming `field`.NAME for a value outside its range.
control::DeadZoneEstimate build_dead_zone(const netmc::v1::DeadZoneSpec& dead_zone, const std::string& field);

}  // namespace netmc::job
