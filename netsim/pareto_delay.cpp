// Heavy-tailed delay (classic Pareto, capped): rare very late packets, as on congested or
// wireless links, which stress the long-delay handling of the controllers.
#include <algorithm>
#include <cmath>
#include <limits>

#include "netsim/delay_model.hpp"
#include "netsim/parameter_check.hpp"
#include "netsim/text_format.hpp"

namespace netmc::netsim {

namespace {

// E[min(X, cap)] = x_m + integral_{x_m}^{cap} (x_m / x)^alpha dx.
double capped_pareto_mean(double scale, double shape, double cap) {
  const double cap_ratio = cap / scale;  // >= 1, may be +inf
  if (shape == 1.0) return scale * (1.0 + std::log(cap_ratio));
  // Also right for cap = +inf: alpha * x_m / (alpha - 1) if alpha > 1, +inf if alpha < 1.
  return scale * (1.0 + (std::pow(cap_ratio, 1.0 - shape) - 1.0) / (1.0 - shape));
}

class ParetoDelay final : public DelayModel {
 public:
  ParetoDelay(double scale_s, double shape, double max_s)
      : scale_s_(scale_s), shape_(shape), max_s_(max_s), mean_s_(capped_pareto_mean(scale_s, shape, max_s)) {}

  double next_delay_s(RandomStream& rng) override {
    const double u = 1.0 - rng.uniform();  // in (0, 1], so the inverse CDF below stays finite
    return std::min(scale_s_ * std::pow(u, -1.0 / shape_), max_s_);
  }

  std::unique_ptr<DelayModel> clone() const override {
    return std::make_unique<ParetoDelay>(scale_s_, shape_, max_s_);
  }

  std::string describe() const override {
    std::string text = "pareto(scale " + format_duration(scale_s_) + ", shape " + format_number(shape_);
    if (std::isfinite(max_s_)) text += ", max " + format_duration(max_s_);
    return text + ")";
  }

  double mean_s() const override { return mean_s_; }

 private:
  double scale_s_;
  double shape_;
  double max_s_;
  double mean_s_;
};

}  // namespace

std::unique_ptr<DelayModel> make_pareto_delay(double scale_s, double shape, double max_s) {
  constexpr const char* model = "pareto delay";
  require_delay(model, "scale", scale_s);
  if (scale_s == 0.0) require_positive(model, "scale", scale_s);  // x_m = 0 is not a Pareto law
  require_positive(model, "shape", shape);
  require_upper_bound(model, "max", max_s, "scale", scale_s);
  return std::make_unique<ParetoDelay>(scale_s, shape, max_s);
}

}  // namespace netmc::netsim
