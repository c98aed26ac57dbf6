#pragma once
// Cross-coupled contour compensation: turns the estimated contour error into a coupling command
// u_e that is distributed to the axes (paper 001, eq. 15).

#include <cstddef>
#include <memory>
#include <string>

namespace netmc::control {

class ContourCompensator {
 public:
  virtual ~ContourCompensator() = default;

  // Start of iteration j over `samples` cycles (ILC prepares u_e,j from iteration j-1 here).
  virtual void begin_iteration(std::size_t samples) = 0;
  // u_e(k) for the contour error eps(k) estimated in cycle k.
  virtual double command(std::size_t cycle, double contour_error) = 0;
  // The gains (cx, cy) of eq. 11/13 that distribute the command of `cycle` to the axes; called
  // just before command(). Only compensators that learn over iterations need them.
  virtual void observe_coupling(std::size_t /*cycle*/, double /*cx*/, double /*cy*/) {}
  // End of iteration j: learning compensators store what they need for j+1.
  virtual void end_iteration() {}

  virtual std::unique_ptr<ContourCompensator> clone() const = 0;
  virtual std::string describe() const = 0;
};

// Per-axis control only: u_e = 0.
class NoContourCompensation final : public ContourCompensator {
 public:
  void begin_iteration(std::size_t) override {}
  double command(std::size_t, double) override { return 0.0; }
  std::unique_ptr<ContourCompensator> clone() const override {
    return std::make_unique<NoContourCompensation>(*this);
  }
  std::string describe() const override { return "none"; }
};

}  // namespace netmc::control
