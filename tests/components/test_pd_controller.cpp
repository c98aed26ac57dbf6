// A controller of the test suite's own, added the way a researcher adds one: this file (the law
// and its descriptor) and one registration line in server/job/controllers/registered_controllers.inc.
// Built only with -DNETMC_TEST_COMPONENTS=ON (the test suite's build, scripts/test.sh), so
// installed netmc does not carry it; integration.own_controller runs it.
//
// The law: u = kp e + kd (e(k) - e(k-1)) / h on the position error e = x_d - y, an axis law that
// composes with every contour compensator (test-pd+ilccc).
#include <fmt/format.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "control/axis/axis_controller.hpp"
#include "server/job/controller_registry.hpp"

namespace netmc::job {
namespace {

class TestProportionalDerivative final : public control::AxisController {
 public:
  TestProportionalDerivative(double kp, double kd, double sample_period_s) : kp_(kp), kd_(kd), h_(sample_period_s) {
    if (!(h_ > 0.0)) throw std::invalid_argument("test-pd: the sample period must be > 0");
  }
  void reset(double) override { previous_error_ = 0.0; }
  double command(double reference, double measured_position) const override {
    const double error = reference - measured_position;
    return kp_ * error + kd_ * (error - previous_error_) / h_;
  }
  void commit(double reference, double measured_position, double, double) override {
    previous_error_ = reference - measured_position;
  }
  std::unique_ptr<control::AxisController> clone() const override {
    return std::make_unique<TestProportionalDerivative>(*this);
  }
  std::string describe() const override { return fmt::format("test-pd kp={:g} kd={:g}", kp_, kd_); }

 private:
  double kp_, kd_, h_;
  double previous_error_ = 0.0;
};

}  // namespace

void register_test_pd(ControllerRegistry& registry) {
  registry.add(GainGroup{"test_pd", "--test-pd", "The test suite's PD law", true,
                         {{"kp", "per m of position error", "540", GainKey::Kind::number, GainCheck::positive},
                          {"kd", "per m/s", "8", GainKey::Kind::number, GainCheck::non_negative}}});
  ControllerFamily family;
  family.names = {"test-pd"};
  family.role = ControllerRole::axis;
  family.summary = "the test suite's PD law (tests/components), built with NETMC_TEST_COMPONENTS only";
  family.source = "textbook";
  family.gain_groups = {"test_pd"};
  family.plants = {"seed001"};
  family.make_axis = [](const ControllerContext& context, std::size_t axis) -> std::unique_ptr<control::AxisController> {
    double kp = 540.0, kd = 8.0;
    context.gains.read("test_pd", "kp", axis, kp);
    context.gains.read("test_pd", "kd", axis, kd);
    return std::make_unique<TestProportionalDerivative>(kp, kd, context.sample_period_s);
  };
  registry.add(std::move(family));
}

}  // namespace netmc::job
