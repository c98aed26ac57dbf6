// The parameter-free and closed-form delay models: none, constant, uniform.
#include "netsim/delay_model.hpp"

#include <stdexcept>

#include "netsim/parameter_check.hpp"
#include "netsim/text_format.hpp"

namespace netmc::netsim {

namespace {

class NoDelay final : public DelayModel {
 public:
  double next_delay_s(RandomStream& /*rng*/) override { return 0.0; }
  std::unique_ptr<DelayModel> clone() const override { return std::make_unique<NoDelay>(); }
  std::string describe() const override { return "no delay"; }
  double mean_s() const override { return 0.0; }
};

class ConstantDelay final : public DelayModel {
 public:
  explicit ConstantDelay(double delay_s) : delay_s_(delay_s) {}
  double next_delay_s(RandomStream& /*rng*/) override { return delay_s_; }
  std::unique_ptr<DelayModel> clone() const override { return std::make_unique<ConstantDelay>(delay_s_); }
  std::string describe() const override { return "constant(" + format_duration(delay_s_) + ")"; }
  double mean_s() const override { return delay_s_; }

 private:
  double delay_s_;
};

class UniformDelay final : public DelayModel {
 public:
  UniformDelay(double min_s, double max_s) : min_s_(min_s), max_s_(max_s) {}
  double next_delay_s(RandomStream& rng) override { return rng.uniform(min_s_, max_s_); }
  std::unique_ptr<DelayModel> clone() const override { return std::make_unique<UniformDelay>(min_s_, max_s_); }
  std::string describe() const override {
    return "uniform(" + format_duration(min_s_) + ", " + format_duration(max_s_) + ")";
  }
  double mean_s() const override { return 0.5 * (min_s_ + max_s_); }

 private:
  double min_s_;
  double max_s_;
};

}  // namespace

std::unique_ptr<DelayModel> make_no_delay() { return std::make_unique<NoDelay>(); }

std::unique_ptr<DelayModel> make_constant_delay(double delay_s) {
  require_delay("constant delay", "delay", delay_s);
  return std::make_unique<ConstantDelay>(delay_s);
}

std::unique_ptr<DelayModel> make_uniform_delay(double min_s, double max_s) {
  require_delay("uniform delay", "min", min_s);
  require_delay("uniform delay", "max", max_s);
  if (min_s > max_s) {
    throw std::invalid_argument("uniform delay: min must be <= max (got min=" + format_number(min_s) +
                                " s, max=" + format_number(max_s) + " s)");
  }
  return std::make_unique<UniformDelay>(min_s, max_s);
}

}  // namespace netmc::netsim
