#pragma once
// PD-type iterative learning cross-coupled control (paper 001, eq. 14): the coupling command of
// iteration j is learned from the contour error of iteration j-1 along the repeated reference.
//   u_e,j(k) = Q[ (1 - forgetting) u_e,j-1(k) + kcp eps_j-1(k+l) + kcd (eps_j-1(k+l) - eps_j-1(k+l-1)) ]
// The paper's law is forgetting = 0, lead l = 0 and Q = identity; the forgetting factor and the
// zero-phase Q-filter keep the learned command bounded under noise and random delay.

#include <vector>

#include "control/cross_coupling/contour_compensator.hpp"
#include "control/cross_coupling/zero_phase_low_pass.hpp"

namespace netmc::control {

struct IterativeLearningGains {
  double kcp = 40.0;
  double kcd = 40.0;
  double forgetting = 0.0;          // in [0, 1)
  double q_cutoff_hz = 0.0;         // <= 0: no Q-filter
  std::size_t lead_samples = 0;     // learn from eps(k + lead)
};

class IterativeLearningCrossCoupling final : public ContourCompensator {
 public:
  IterativeLearningCrossCoupling(const IterativeLearningGains& gains, double sample_period_s);

  void begin_iteration(std::size_t samples) override;
  double command(std::size_t cycle, double contour_error) override;
  void end_iteration() override;
  std::unique_ptr<ContourCompensator> clone() const override;
  std::string describe() const override;

  // u_e,j of the current iteration (the learning memory).
  const std::vector<double>& learned_command() const { return command_; }
  std::size_t completed_iterations() const { return completed_iterations_; }

 private:
  IterativeLearningGains gains_;
  ZeroPhaseLowPass q_filter_;
  std::vector<double> command_;          // u_e,j
  std::vector<double> previous_error_;   // eps_j-1
  std::vector<double> current_error_;    // eps_j, being recorded
  std::size_t completed_iterations_ = 0;
};

}  // namespace netmc::control
