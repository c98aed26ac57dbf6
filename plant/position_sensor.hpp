#pragma once
// Position measurement of an axis: Gaussian noise, then encoder quantisation (paper 000 uses a
// 0.5 um linear encoder, section 2.5.1; appendix A.1.2 once prints 0.5 nm). Noise is drawn from
// netsim::RandomStream so a run is reproducible from its seed on any platform.

#include <cstdint>

#include "netsim/random_stream.hpp"

namespace netmc::plant {

struct PositionSensorParameters {
  double resolution_m = 0.0;    // encoder count (m); 0 = no quantisation
  double noise_stddev_m = 0.0;  // Gaussian noise standard deviation (m); 0 = no noise
};

class PositionSensor {
 public:
  PositionSensor(PositionSensorParameters p, std::uint64_t seed, std::uint64_t stream);

  // Noise added, then quantised to the nearest multiple of the resolution (a NaN passes through).
  double measure(double true_position);
  // Restart the noise stream (same seed and stream: the same noise sequence again).
  void reset();

  const PositionSensorParameters& parameters() const { return p_; }

 private:
  PositionSensorParameters p_;
  std::uint64_t seed_;
  std::uint64_t stream_;
  netsim::RandomStream rng_;
};

}  // namespace netmc::plant
