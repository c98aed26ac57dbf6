#include "control/cross_coupling/tustin_cross_coupling.hpp"

#include "control/parameter_check.hpp"

namespace netmc::control {

TustinCrossCoupling::TustinCrossCoupling(const TransferFunction& law, double sample_period_s, std::string name)
    : continuous_(law),
      discrete_(tustin(continuous_, sample_period_s)),
      filter_(discrete_),
      name_(std::move(name)) {}

void TustinCrossCoupling::begin_iteration(std::size_t /*samples*/) { filter_.reset(); }

double TustinCrossCoupling::command(std::size_t /*cycle*/, double contour_error) {
  return filter_.step(contour_error);
}

std::unique_ptr<ContourCompensator> TustinCrossCoupling::clone() const {
  return std::make_unique<TustinCrossCoupling>(*this);
}

std::string TustinCrossCoupling::describe() const { return name_ + "(C(s) = " + continuous_.describe() + ")"; }

TustinCrossCoupling make_low_pass_pid_cross_coupling(const FilteredPidCrossCouplingGains& gains,
                                                     double sample_period_s) {
  require_finite(gains.kp, "lpccc kp");
  require_finite(gains.ki, "lpccc ki");
  require_finite(gains.kd, "lpccc kd");
  require_positive(gains.low_pass_hz, "lpccc low_pass_hz");
  require_positive(gains.low_pass_damping, "lpccc low_pass_damping");
  return {paper004_pid_cross_coupling(gains), sample_period_s, "lpccc"};  // eq. 13
}

TustinCrossCoupling make_qft_cross_coupling(double sample_period_s) {
  return {paper004_eq20_cross_coupling(), sample_period_s, "qftccc"};  // eq. 20
}

}  // namespace netmc::control
