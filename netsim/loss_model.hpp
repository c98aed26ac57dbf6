#pragma once
// Packet loss models for one link direction: one drop decision per packet from a caller-owned
// RandomStream, so a run with a given seed is bit-identical. Build models with the make_*
// factories; probabilities must lie in [0, 1] (std::invalid_argument otherwise).

#include <memory>
#include <string>

#include "netsim/random_stream.hpp"

namespace netmc::netsim {

class LossModel {
 public:
  virtual ~LossModel() = default;
  virtual bool drop(RandomStream& rng) = 0;   // one decision per packet
  virtual void reset() {}                      // back to the initial state (Gilbert-Elliott: good)
  virtual std::unique_ptr<LossModel> clone() const = 0;  // same parameters, initial state
  virtual std::string describe() const = 0;    // e.g. "bernoulli(p 0.01)"
  virtual double mean_loss_rate() const = 0;  // stationary loss probability
};

std::unique_ptr<LossModel> make_no_loss();

// Independent losses with probability p per packet.
std::unique_ptr<LossModel> make_bernoulli_loss(double p);

// Bursty losses: a good/bad Markov chain (starting in good) with per-state loss probabilities.
// Each packet is dropped with its current state's probability, then the state switches.
std::unique_ptr<LossModel> make_gilbert_elliott_loss(double p_good_to_bad, double p_bad_to_good, double loss_in_good,
                                                     double loss_in_bad);

}  // namespace netmc::netsim
