#pragma once
// Zero-phase low-pass for whole recorded signals (the ILC Q-filter): a first-order filter run
// forward and then backward, so it attenuates noise without shifting the learned command in time.

#include <cstddef>
#include <vector>

namespace netmc::control {

class ZeroPhaseLowPass {
 public:
  // cutoff_hz <= 0 disables the filter (identity).
  ZeroPhaseLowPass(double cutoff_hz, double sample_period_s);

  void apply(std::vector<double>& signal) const { apply(signal, 0, signal.size()); }
  // Filters signal[begin, end) as a signal of its own (each pass starts at that piece's edge).
  void apply(std::vector<double>& signal, std::size_t begin, std::size_t end) const;
  bool enabled() const { return enabled_; }

 private:
  bool enabled_;
  double pole_ = 0.0;  // y(k) = pole*y(k-1) + (1-pole)*x(k)
};

}  // namespace netmc::control
