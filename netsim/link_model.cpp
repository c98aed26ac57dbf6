#include "netsim/link_model.hpp"

#include <stdexcept>
#include <utility>

namespace netmc::netsim {

LinkModel::LinkModel(std::unique_ptr<DelayModel> delay, std::unique_ptr<LossModel> loss, RandomStream rng)
    : delay_(std::move(delay)), loss_(std::move(loss)), rng_(rng) {
  if (!delay_) throw std::invalid_argument("link model: delay must be a delay model (got null)");
  if (!loss_) throw std::invalid_argument("link model: loss must be a loss model (got null)");
}

LinkModel::LinkModel(const LinkModel& other)
    : delay_(other.delay_->clone()), loss_(other.loss_->clone()), rng_(other.rng_) {}

LinkModel& LinkModel::operator=(const LinkModel& other) {
  if (this != &other) {
    LinkModel copy(other);  // clone first: if cloning throws, *this is untouched
    *this = std::move(copy);
  }
  return *this;
}

LinkModel::Transit LinkModel::transmit() {
  const bool lost = loss_->drop(rng_);
  const double delay_s = delay_->next_delay_s(rng_);
  return Transit{lost, delay_s};
}

void LinkModel::reset(RandomStream rng) {
  delay_->reset();
  loss_->reset();
  rng_ = rng;
}

std::string LinkModel::describe() const { return "delay " + delay_->describe() + ", loss " + loss_->describe(); }

const DelayModel& LinkModel::delay_model() const { return *delay_; }

const LossModel& LinkModel::loss_model() const { return *loss_; }

}  // namespace netmc::netsim
