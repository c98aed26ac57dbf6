// Bursty delay: a two-state (good/bad) Markov chain picks which delay model serves each
// packet, so congestion episodes produce runs of long delays rather than isolated ones.
#include <stdexcept>

#include "netsim/delay_model.hpp"
#include "netsim/parameter_check.hpp"
#include "netsim/text_format.hpp"

namespace netmc::netsim {

namespace {

class MarkovDelay final : public DelayModel {
 public:
  MarkovDelay(std::unique_ptr<DelayModel> good, std::unique_ptr<DelayModel> bad, double p_good_to_bad,
              double p_bad_to_good)
      : good_(std::move(good)), bad_(std::move(bad)), p_good_to_bad_(p_good_to_bad), p_bad_to_good_(p_bad_to_good) {}

  double next_delay_s(RandomStream& rng) override {
    const double delay_s = in_bad_state_ ? bad_->next_delay_s(rng) : good_->next_delay_s(rng);
    // Always one switch draw per packet, so the stream position does not depend on the state.
    const double switch_draw = rng.uniform();
    in_bad_state_ = in_bad_state_ ? !(switch_draw < p_bad_to_good_) : switch_draw < p_good_to_bad_;
    return delay_s;
  }

  void reset() override {
    in_bad_state_ = false;
    good_->reset();
    bad_->reset();
  }

  std::unique_ptr<DelayModel> clone() const override {
    return std::make_unique<MarkovDelay>(good_->clone(), bad_->clone(), p_good_to_bad_, p_bad_to_good_);
  }

  std::string describe() const override {
    return "markov(good " + good_->describe() + ", bad " + bad_->describe() + ", p_good_to_bad " +
           format_number(p_good_to_bad_) + ", p_bad_to_good " + format_number(p_bad_to_good_) + ")";
  }

  double mean_s() const override {
    const double switch_sum = p_good_to_bad_ + p_bad_to_good_;
    // A chain that never switches stays in its initial (good) state.
    const double bad_fraction = switch_sum > 0.0 ? p_good_to_bad_ / switch_sum : 0.0;
    // Skip a state that is never visited, so an infinite mean there cannot turn into 0 * inf.
    if (bad_fraction == 0.0) return good_->mean_s();
    if (bad_fraction == 1.0) return bad_->mean_s();
    return (1.0 - bad_fraction) * good_->mean_s() + bad_fraction * bad_->mean_s();
  }

 private:
  std::unique_ptr<DelayModel> good_;
  std::unique_ptr<DelayModel> bad_;
  double p_good_to_bad_;
  double p_bad_to_good_;
  bool in_bad_state_ = false;
};

}  // namespace

std::unique_ptr<DelayModel> make_markov_delay(std::unique_ptr<DelayModel> good, std::unique_ptr<DelayModel> bad,
                                              double p_good_to_bad, double p_bad_to_good) {
  constexpr const char* model = "markov delay";
  if (!good) throw std::invalid_argument("markov delay: good must be a delay model (got null)");
  if (!bad) throw std::invalid_argument("markov delay: bad must be a delay model (got null)");
  require_probability(model, "p_good_to_bad", p_good_to_bad);
  require_probability(model, "p_bad_to_good", p_bad_to_good);
  return std::make_unique<MarkovDelay>(std::move(good), std::move(bad), p_good_to_bad, p_bad_to_good);
}

}  // namespace netmc::netsim
