#include "plant/position_sensor.hpp"

#include <cmath>

#include "plant/parameter_checks.hpp"

namespace netmc::plant {
namespace {

constexpr const char* kPositionSensorOwner = "PositionSensor";

PositionSensorParameters validated(PositionSensorParameters p) {
  require_non_negative(kPositionSensorOwner, "resolution_m", p.resolution_m);
  require_non_negative(kPositionSensorOwner, "noise_stddev_m", p.noise_stddev_m);
  return p;
}

}  // namespace

PositionSensor::PositionSensor(PositionSensorParameters p, std::uint64_t seed, std::uint64_t stream)
    : p_(validated(p)), seed_(seed), stream_(stream), rng_(seed, stream) {}

double PositionSensor::measure(double true_position) {
  double y = true_position;
  // No draw when the noise is off, so enabling quantisation alone leaves the stream untouched.
  if (p_.noise_stddev_m > 0.0) y += p_.noise_stddev_m * rng_.standard_normal();
  if (p_.resolution_m > 0.0) y = p_.resolution_m * std::round(y / p_.resolution_m);
  return y;
}

void PositionSensor::reset() { rng_ = netsim::RandomStream(seed_, stream_); }

}  // namespace netmc::plant
