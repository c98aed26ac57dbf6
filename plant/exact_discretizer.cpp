#include "plant/exact_discretizer.hpp"

#include <unsupported/Eigen/MatrixFunctions>

namespace netmc::plant {

ExactDiscretizer::ExactDiscretizer(const Eigen::Matrix2d& a, const Eigen::Vector2d& b)
    : a_(a), b_(b) {}

const ExactDiscretizer::Transition& ExactDiscretizer::transition(double h) {
  ++clock_;
  // Fast path: the same duration as last time (fixed period, no delay).
  if (count_ > 0 && keys_[last_hit_] == h) {
    last_use_[last_hit_] = clock_;
    return entries_[last_hit_];
  }
  for (std::size_t i = 0; i < count_; ++i) {
    if (keys_[i] == h) {
      last_hit_ = i;
      last_use_[i] = clock_;
      return entries_[i];
    }
  }
  // Miss: fill a free slot or evict the least recently used one, so a period that recurs every
  // cycle survives a stream of one-off (random tau) durations.
  std::size_t slot = count_;
  if (count_ < kCacheSize) {
    ++count_;
  } else {
    slot = 0;
    for (std::size_t i = 1; i < kCacheSize; ++i) {
      if (last_use_[i] < last_use_[slot]) slot = i;
    }
  }
  ++misses_;
  Eigen::Matrix3d augmented = Eigen::Matrix3d::Zero();
  augmented.topLeftCorner<2, 2>() = a_ * h;
  augmented.topRightCorner<2, 1>() = b_ * h;
  const Eigen::Matrix3d e = augmented.exp();
  entries_[slot].phi = e.topLeftCorner<2, 2>();
  entries_[slot].gamma = e.topRightCorner<2, 1>();
  keys_[slot] = h;
  last_use_[slot] = clock_;
  last_hit_ = slot;
  return entries_[slot];
}

}  // namespace netmc::plant
