// The memoryless loss models: none and Bernoulli.
#include "netsim/loss_model.hpp"

#include "netsim/parameter_check.hpp"
#include "netsim/text_format.hpp"

namespace netmc::netsim {

namespace {

class NoLoss final : public LossModel {
 public:
  bool drop(RandomStream& /*rng*/) override { return false; }
  std::unique_ptr<LossModel> clone() const override { return std::make_unique<NoLoss>(); }
  std::string describe() const override { return "no loss"; }
  double mean_loss_rate() const override { return 0.0; }
};

class BernoulliLoss final : public LossModel {
 public:
  explicit BernoulliLoss(double p) : p_(p) {}
  // uniform() is in [0, 1): p = 0 never drops, p = 1 always drops.
  bool drop(RandomStream& rng) override { return rng.uniform() < p_; }
  std::unique_ptr<LossModel> clone() const override { return std::make_unique<BernoulliLoss>(p_); }
  std::string describe() const override { return "bernoulli(p " + format_number(p_) + ")"; }
  double mean_loss_rate() const override { return p_; }

 private:
  double p_;
};

}  // namespace

std::unique_ptr<LossModel> make_no_loss() { return std::make_unique<NoLoss>(); }

std::unique_ptr<LossModel> make_bernoulli_loss(double p) {
  require_probability("bernoulli loss", "p", p);
  return std::make_unique<BernoulliLoss>(p);
}

}  // namespace netmc::netsim
