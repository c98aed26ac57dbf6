#pragma once
// Common interface of every simulated axis: the axis node and the in-process sim drive all plants
// through it, one held input per call (paper 001, eq. 2, cited but not printed in the source text;
// read from its Fig. 4 and eq. 4).
// See docs/architecture.md, "Layers and include rules".

#include <memory>
#include <string>

namespace netmc::plant {

class AxisPlant {
 public:
  virtual ~AxisPlant() = default;

  // All internal states (modes, time) reset; t = 0.
  virtual void reset(double position, double velocity) = 0;
  // Input held constant over [t, t + duration); duration >= 0 (0 is a no-op).
  virtual void advance(double duration_s, double input) = 0;
  virtual double position() const = 0;  // true position (m)
  virtual double velocity() const = 0;  // true velocity (m/s)
  virtual double time() const = 0;      // time since reset (s)
  // Same parameters, same current state.
  virtual std::unique_ptr<AxisPlant> clone() const = 0;
  // One line with the key parameters.
  virtual std::string describe() const = 0;

 protected:
  AxisPlant() = default;
  AxisPlant(const AxisPlant&) = default;
  AxisPlant& operator=(const AxisPlant&) = default;
  AxisPlant(AxisPlant&&) = default;
  AxisPlant& operator=(AxisPlant&&) = default;
};

}  // namespace netmc::plant
