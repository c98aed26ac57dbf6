#pragma once
// PD-type iterative learning cross-coupled control (paper 001, eq. 14): the coupling command of
// iteration j is learned from the contour error of iteration j-1 along the repeated reference.
//   u_e,j(k) = Q[ (1 - forgetting) u_e,j-1(k) + kcp eps_j-1(k+l) + kcd (eps_j-1(k+l) - eps_j-1(k+l-1)) ]
// The paper's law is forgetting = 0, lead l = 0 and Q = identity; the forgetting factor and the
// zero-phase Q-filter keep the learned command bounded under noise and random delay.
//
// Coupling switches: where the coupling direction (cx, cy) of eq. 11/13 jumps between two cycles
// (a sharp corner of the contour, not a smooth turn), the learning law is split into sections
// at the jump (see begin_iteration). A contour without such jumps (circle, ellipse, spline,
// Lissajous) is one section, and the law above is applied unchanged.

#include <cstddef>
#include <numbers>
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
  // A coupling switch: consecutive coupling directions more than this apart (a smooth contour
  // turns by feed*h*curvature per cycle: 0.23 deg on paper 001's circle).
  double switch_angle_rad = std::numbers::pi / 12.0;
  // Errors of the first cycles after a switch are not learned from: they are set by the motion
  // before it, which no coupling command could act on (the relative degree of position, 2).
  std::size_t switch_blind_samples = 2;
};

class IterativeLearningCrossCoupling final : public ContourCompensator {
 public:
  IterativeLearningCrossCoupling(const IterativeLearningGains& gains, double sample_period_s);

  void begin_iteration(std::size_t samples) override;
  void observe_coupling(std::size_t cycle, double cx, double cy) override;
  double command(std::size_t cycle, double contour_error) override;
  void end_iteration() override;
  std::unique_ptr<ContourCompensator> clone() const override;
  std::string describe() const override;

  // u_e,j of the current iteration (the learning memory).
  const std::vector<double>& learned_command() const { return command_; }
  std::size_t completed_iterations() const { return completed_iterations_; }
  // The first cycles of the learning sections of the current iteration: 0, then each coupling
  // switch found in iteration j-1.
  const std::vector<std::size_t>& section_starts() const { return section_starts_; }

 private:
  struct Direction {
    double cx = 0.0, cy = 0.0;
  };
  void find_sections(std::size_t samples);

  IterativeLearningGains gains_;
  ZeroPhaseLowPass q_filter_;
  std::vector<double> command_;             // u_e,j
  std::vector<double> previous_error_;      // eps_j-1
  std::vector<double> current_error_;       // eps_j, being recorded
  std::vector<Direction> previous_coupling_;  // (cx, cy) of iteration j-1
  std::vector<Direction> current_coupling_;   // of iteration j, being recorded
  std::vector<std::size_t> section_starts_{0};
  std::size_t completed_iterations_ = 0;
};

}  // namespace netmc::control
