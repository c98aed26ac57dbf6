#include "control/cross_coupling/iterative_learning_cross_coupling.hpp"

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
}

void IterativeLearningCrossCoupling::begin_iteration(std::size_t samples) {
  // A changed run length keeps what overlaps; the rest starts from zero.
  command_.resize(samples, 0.0);
  previous_error_.resize(samples, 0.0);
  std::vector<double> next(samples, 0.0);
  const auto error_at = [&](std::size_t index) {
    return index < samples ? previous_error_[index] : 0.0;
  };
  for (std::size_t k = 0; k < samples; ++k) {
    const std::size_t i = k + gains_.lead_samples;
    const double error = error_at(i);
    const double earlier = i == 0 ? 0.0 : error_at(i - 1);  // eps_j(-1) = 0
    next[k] = (1.0 - gains_.forgetting) * command_[k] + gains_.kcp * error +
              gains_.kcd * (error - earlier);  // paper 001, eq. 14
  }
  q_filter_.apply(next);
  command_ = std::move(next);
  current_error_.assign(samples, 0.0);
}

double IterativeLearningCrossCoupling::command(std::size_t cycle, double contour_error) {
  if (cycle >= command_.size()) return 0.0;
  current_error_[cycle] = contour_error;
  return command_[cycle];
}

void IterativeLearningCrossCoupling::end_iteration() {
  previous_error_ = current_error_;
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
