// Gilbert-Elliott burst loss: a two-state Markov chain whose bad state loses packets far more
// often, giving the loss runs seen on real links rather than isolated drops.
#include "netsim/loss_model.hpp"
#include "netsim/parameter_check.hpp"
#include "netsim/text_format.hpp"

namespace netmc::netsim {

namespace {

class GilbertElliottLoss final : public LossModel {
 public:
  GilbertElliottLoss(double p_good_to_bad, double p_bad_to_good, double loss_in_good, double loss_in_bad)
      : p_good_to_bad_(p_good_to_bad),
        p_bad_to_good_(p_bad_to_good),
        loss_in_good_(loss_in_good),
        loss_in_bad_(loss_in_bad) {}

  bool drop(RandomStream& rng) override {
    // Two draws per packet whatever the state, so the stream position is predictable.
    const bool dropped = rng.uniform() < (in_bad_state_ ? loss_in_bad_ : loss_in_good_);
    const double switch_draw = rng.uniform();
    in_bad_state_ = in_bad_state_ ? !(switch_draw < p_bad_to_good_) : switch_draw < p_good_to_bad_;
    return dropped;
  }

  void reset() override { in_bad_state_ = false; }

  std::unique_ptr<LossModel> clone() const override {
    return std::make_unique<GilbertElliottLoss>(p_good_to_bad_, p_bad_to_good_, loss_in_good_, loss_in_bad_);
  }

  std::string describe() const override {
    return "gilbert_elliott(p_good_to_bad " + format_number(p_good_to_bad_) + ", p_bad_to_good " +
           format_number(p_bad_to_good_) + ", loss_in_good " + format_number(loss_in_good_) + ", loss_in_bad " +
           format_number(loss_in_bad_) + ")";
  }

  double mean_loss_rate() const override {
    const double switch_sum = p_good_to_bad_ + p_bad_to_good_;
    // A chain that never switches stays in its initial (good) state.
    const double bad_fraction = switch_sum > 0.0 ? p_good_to_bad_ / switch_sum : 0.0;
    return (1.0 - bad_fraction) * loss_in_good_ + bad_fraction * loss_in_bad_;
  }

 private:
  double p_good_to_bad_;
  double p_bad_to_good_;
  double loss_in_good_;
  double loss_in_bad_;
  bool in_bad_state_ = false;
};

}  // namespace

std::unique_ptr<LossModel> make_gilbert_elliott_loss(double p_good_to_bad, double p_bad_to_good, double loss_in_good,
                                                     double loss_in_bad) {
  constexpr const char* model = "gilbert-elliott loss";
  require_probability(model, "p_good_to_bad", p_good_to_bad);
  require_probability(model, "p_bad_to_good", p_bad_to_good);
  require_probability(model, "loss_in_good", loss_in_good);
  require_probability(model, "loss_in_bad", loss_in_bad);
  return std::make_unique<GilbertElliottLoss>(p_good_to_bad, p_bad_to_good, loss_in_good, loss_in_bad);
}

}  // namespace netmc::netsim
