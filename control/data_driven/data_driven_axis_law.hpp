#pragma once
// One axis of a data-driven contouring controller (paper 002): each sample it sees the measured
// position, the desired positions now and one sample ahead, and this axis's component of the
// estimated contour-error vector, all in the controller's length unit, and returns u(k).

#include <memory>
#include <string>

namespace netmc::control {

struct NamedEstimate {
  const char* name;  // e.g. "phi_hat"
  const char* unit;  // e.g. "um/V"
  double value;
};

class DataDrivenAxisLaw {
 public:
  virtual ~DataDrivenAxisLaw() = default;
  virtual void reset(double position) = 0;
  virtual double command(double position, double desired, double desired_next, double contour_error) = 0;
  virtual std::unique_ptr<DataDrivenAxisLaw> clone() const = 0;
  virtual std::string describe() const = 0;
  // The law's internal estimates after the last command (Phi^, Psi^, d^, s ...).
  virtual std::size_t estimate_count() const = 0;
  virtual NamedEstimate estimate(std::size_t index) const = 0;
};

}  // namespace netmc::control
