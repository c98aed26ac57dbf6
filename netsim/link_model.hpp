#pragma once
// One direction of a network link: a delay model, a loss model and the link's own random
// stream. Giving each link its own stream keeps links independent: adding a link or changing
// one link's models leaves the draws of every other link unchanged.

#include <memory>
#include <string>

#include "netsim/delay_model.hpp"
#include "netsim/loss_model.hpp"
#include "netsim/random_stream.hpp"

namespace netmc::netsim {

class LinkModel {
 public:
  // Throws std::invalid_argument if a model is null.
  LinkModel(std::unique_ptr<DelayModel> delay, std::unique_ptr<LossModel> loss, RandomStream rng);
  // Deep copy: the models are cloned (clones start from their initial state) and the stream
  // state is copied, so a copy of a fresh link replays exactly what the original will draw.
  LinkModel(const LinkModel& other);
  LinkModel& operator=(const LinkModel& other);
  LinkModel(LinkModel&&) noexcept = default;
  LinkModel& operator=(LinkModel&&) noexcept = default;
  ~LinkModel() = default;

  struct Transit {
    bool lost;
    double delay_s;  // drawn even for a lost packet
  };

  // Draws loss first, then delay; both are always drawn so the stream position does not
  // depend on whether the packet was lost.
  Transit transmit();

  void reset(RandomStream rng);  // models back to their initial state, new stream
  std::string describe() const;  // "delay <model>, loss <model>"
  const DelayModel& delay_model() const;
  const LossModel& loss_model() const;

 private:
  std::unique_ptr<DelayModel> delay_;
  std::unique_ptr<LossModel> loss_;
  RandomStream rng_;
};

}  // namespace netmc::netsim
