// Replay of recorded delays, so a study can use a delay profile measured on a real network.
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "netsim/delay_model.hpp"
#include "netsim/parameter_check.hpp"
#include "netsim/text_format.hpp"

namespace netmc::netsim {

namespace {

class TraceDelay final : public DelayModel {
 public:
  // Clones share the immutable samples: traces can hold millions of entries.
  explicit TraceDelay(std::shared_ptr<const std::vector<double>> delays_s)
      : delays_s_(std::move(delays_s)),
        mean_s_(std::accumulate(delays_s_->begin(), delays_s_->end(), 0.0) /
                static_cast<double>(delays_s_->size())) {}

  double next_delay_s(RandomStream& /*rng*/) override {
    const double delay_s = (*delays_s_)[next_index_];
    next_index_ = (next_index_ + 1) % delays_s_->size();
    return delay_s;
  }

  void reset() override { next_index_ = 0; }

  std::unique_ptr<DelayModel> clone() const override { return std::make_unique<TraceDelay>(delays_s_); }

  std::string describe() const override {
    return "trace(" + std::to_string(delays_s_->size()) + " samples, mean " + format_duration(mean_s_) + ")";
  }

  double mean_s() const override { return mean_s_; }

 private:
  std::shared_ptr<const std::vector<double>> delays_s_;
  double mean_s_;
  std::size_t next_index_ = 0;
};

}  // namespace

std::unique_ptr<DelayModel> make_trace_delay(std::vector<double> delays_s) {
  if (delays_s.empty()) {
    throw std::invalid_argument("trace delay: delays_s must hold at least one delay (got an empty trace)");
  }
  if (delays_s.size() > kMaxDelayTraceSamples) {
    throw std::invalid_argument("trace delay: delays_s holds " + std::to_string(delays_s.size()) +
                                " samples, more than " + std::to_string(kMaxDelayTraceSamples));
  }
  for (std::size_t i = 0; i < delays_s.size(); ++i) {
    if (!(std::isfinite(delays_s[i]) && delays_s[i] >= 0.0 && delays_s[i] <= kMaxDelayS)) {
      throw std::invalid_argument("trace delay: delays_s[" + std::to_string(i) + "] must be a delay in [0, " +
                                  format_number(kMaxDelayS) + "] s (got " + format_number(delays_s[i]) + " s)");
    }
  }
  return std::make_unique<TraceDelay>(std::make_shared<const std::vector<double>>(std::move(delays_s)));
}

}  // namespace netmc::netsim
