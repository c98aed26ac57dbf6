#pragma once
// A continuous-time cross-coupling controller C(s), u_c = C ε_c, run as its Tustin
// discretisation at the loop rate: paper 004's PID-CCC with low-pass (eq. 13, Table 3) and its
// QFT design (eq. 20).

#include <string>

#include "control/cross_coupling/contour_compensator.hpp"
#include "control/frequency/qft_bounds.hpp"
#include "control/frequency/tustin.hpp"

namespace netmc::control {

class TustinCrossCoupling final : public ContourCompensator {
 public:
  // `name` is what describe() reports; throws std::invalid_argument for an improper C(s) or a
  // sample period Tustin refuses.
  TustinCrossCoupling(const TransferFunction& law, double sample_period_s, std::string name);

  void begin_iteration(std::size_t samples) override;
  // u_c(k) = C(z) ε_c(k); one filter step, no allocation.
  double command(std::size_t cycle, double contour_error) override;
  std::unique_ptr<ContourCompensator> clone() const override;
  std::string describe() const override;

  const TransferFunction& continuous_law() const { return continuous_; }
  const DiscreteTransferFunction& discrete_law() const { return discrete_; }

 private:
  TransferFunction continuous_;
  DiscreteTransferFunction discrete_;
  DiscreteFilter filter_;
  std::string name_;
};

// paper 004, eq. 13 with `gains` (Table 3 by default): "lpccc".
TustinCrossCoupling make_low_pass_pid_cross_coupling(const FilteredPidCrossCouplingGains& gains,
                                                     double sample_period_s);
// paper 004, eq. 20: "qftccc".
TustinCrossCoupling make_qft_cross_coupling(double sample_period_s);

}  // namespace netmc::control
