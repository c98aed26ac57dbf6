#include "control/cross_coupling/iterative_learning_cross_coupling.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "control/parameter_check.hpp"

namespace netmc::control {

IterativeLearningCrossCoupling::IterativeLearningCrossCoupling(
    const IterativeLearningGains& gains, double sample_period_s)
    : gains_(gains), q_filter_(gains.q_cutoff_hz, sample_period_s) {
  require_finite(gains.kcp, "ilccc kcp");
  require_finite(gains.kcd, "ilccc kcd");
  if (!(gains.forgetting >= 0.0 && gains.forgetting < 1.0)) {
    throw std::invalid_argument("ilccc forgetting: expected a number in [0, 1), got " +
                                std::to_string(gains.forgetting));
  }
  if (!(gains.switch_angle_rad > 0.0 && gains.switch_angle_rad <= std::numbers::pi)) {
    throw std::invalid_argument("ilccc switch angle: expected a number in (0, pi], got " +
                                std::to_string(gains.switch_angle_rad));
  }
}

// Why sections. At a sharp corner the coupling direction jumps from the normal of one segment
// to that of the next, so the scalar u_e pushes a different axis on each side, and the contour
// error of the first cycles after the jump is the along-track lag of the previous segment seen
// along the new normal. No coupling command can change it: the earlier ones acted along the old
// normal, orthogonal to it, and the new ones reach the position only after the relative degree.
// Learning from it breaks the convergence of eq. 14 (an error outside the reach of the input
// is integrated every iteration: u_e at the corner grows by kcp*eps + kcd*d(eps) each time, and
// the growing pulse overshoots the next segment), and a Q-filter run across the jump leaks the
// pulse into the previous segment, where it drives the other axis. So the errors of the first
// `switch_blind_samples` cycles after a switch, and differences eps(i) - eps(i-1) that involve
// them or cross the switch, are not learned from (as ILC leaves out the first relative-degree
// samples after an initial condition), and the Q-filter runs on each section separately.
void IterativeLearningCrossCoupling::find_sections(std::size_t samples) {
  section_starts_.assign(1, 0);
  const double cos_switch = std::cos(gains_.switch_angle_rad);
  for (std::size_t k = 1; k < samples; ++k) {
    const Direction& a = previous_coupling_[k - 1];
    const Direction& b = previous_coupling_[k];
    const double norms = std::hypot(a.cx, a.cy) * std::hypot(b.cx, b.cy);
    if (!(norms > 0.0)) continue;  // not recorded: no switch
    if ((a.cx * b.cx + a.cy * b.cy) < cos_switch * norms) section_starts_.push_back(k);
  }
}

void IterativeLearningCrossCoupling::begin_iteration(std::size_t samples) {
  // A changed run length keeps what overlaps; the rest starts from zero.
  command_.resize(samples, 0.0);
  previous_error_.resize(samples, 0.0);
  previous_coupling_.resize(samples);
  find_sections(samples);
  std::vector<double> next(samples, 0.0);
  const auto error_at = [&](std::size_t index) {
    return index < samples ? previous_error_[index] : 0.0;
  };
  std::size_t section = 0;  // the section of error sample i (i grows with k)
  for (std::size_t k = 0; k < samples; ++k) {
    const std::size_t i = k + gains_.lead_samples;
    while (section + 1 < section_starts_.size() && section_starts_[section + 1] <= i) ++section;
    const std::size_t start = section_starts_[section];
    // The first `switch_blind_samples` errors of a section, and the difference that reaches
    // back to the last of them (or across the switch), are not learned from.
    if (start > 0 && i < samples && i <= start + gains_.switch_blind_samples) {
      next[k] = (1.0 - gains_.forgetting) * command_[k];  // not reachable: keep, do not learn
      continue;
    }
    const double error = error_at(i);
    const double earlier = i == 0 ? 0.0 : error_at(i - 1);  // eps_j(-1) = 0
    next[k] = (1.0 - gains_.forgetting) * command_[k] + gains_.kcp * error +
              gains_.kcd * (error - earlier);  // paper 001, eq. 14
  }
  for (std::size_t s = 0; s < section_starts_.size(); ++s) {
    const std::size_t end = s + 1 < section_starts_.size() ? section_starts_[s + 1] : samples;
    q_filter_.apply(next, section_starts_[s], end);
  }
  command_ = std::move(next);
  current_error_.assign(samples, 0.0);
  current_coupling_.assign(samples, Direction{});
}

void IterativeLearningCrossCoupling::observe_coupling(std::size_t cycle, double cx, double cy) {
  if (cycle < current_coupling_.size()) current_coupling_[cycle] = {cx, cy};
}

double IterativeLearningCrossCoupling::command(std::size_t cycle, double contour_error) {
  if (cycle >= command_.size()) return 0.0;
  current_error_[cycle] = contour_error;
  return command_[cycle];
}

void IterativeLearningCrossCoupling::end_iteration() {
  previous_error_ = current_error_;
  previous_coupling_ = current_coupling_;
  ++completed_iterations_;
}

std::unique_ptr<ContourCompensator> IterativeLearningCrossCoupling::clone() const {
  return std::make_unique<IterativeLearningCrossCoupling>(*this);
}

std::string IterativeLearningCrossCoupling::describe() const {
  std::ostringstream text;
  text << "ilccc(kcp=" << gains_.kcp << ", kcd=" << gains_.kcd;
  if (gains_.forgetting > 0.0) text << ", forgetting=" << gains_.forgetting;
  if (q_filter_.enabled()) text << ", q=" << gains_.q_cutoff_hz << " Hz";
  if (gains_.lead_samples > 0) text << ", lead=" << gains_.lead_samples;
  text << ")";
  return text.str();
}

}  // namespace netmc::control
