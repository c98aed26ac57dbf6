#pragma once
// Exact discretisation of a two-state linear system z' = A z + B w with w held constant over a
// step of length h (zero-order hold): z(t + h) = Phi(h) z(t) + Gamma(h) w, taken from the matrix
// exponential of the augmented system, exp([[A, B], [0, 0]] h) = [[Phi, Gamma], [0, 1]].
// netmc's choice [A]: the plants integrate paper 001 eq. 3 exactly on each sub-interval of a period
// (the paper's discretisations, eq. 4-5, are for its analysis).
//
// Durations repeat (the period h, or tau and h - tau), so (Phi, Gamma) is cached per exact
// duration value in a small least-recently-used table. Everything is fixed-size: step() never
// touches the heap.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>

namespace netmc::plant {

class ExactDiscretizer {
 public:
  struct Transition {
    Eigen::Matrix2d phi = Eigen::Matrix2d::Identity();
    Eigen::Vector2d gamma = Eigen::Vector2d::Zero();
  };

  ExactDiscretizer() = default;  // z' = 0
  ExactDiscretizer(const Eigen::Matrix2d& a, const Eigen::Vector2d& b);

  // (Phi(h), Gamma(h)) for a finite h >= 0; computed once per distinct h while it stays cached.
  const Transition& transition(double h);

  // z <- Phi(h) z + Gamma(h) w.
  void step(Eigen::Vector2d& z, double h, double w) {
    const Transition& tr = transition(h);
    const Eigen::Vector2d next = tr.phi * z + tr.gamma * w;
    z = next;
  }

  const Eigen::Matrix2d& a() const { return a_; }
  const Eigen::Vector2d& b() const { return b_; }
  std::size_t cached_count() const { return count_; }
  std::uint64_t miss_count() const { return misses_; }

  static constexpr std::size_t kCacheSize = 8;

 private:
  Eigen::Matrix2d a_ = Eigen::Matrix2d::Zero();
  Eigen::Vector2d b_ = Eigen::Vector2d::Zero();
  std::array<double, kCacheSize> keys_{};
  std::array<std::uint64_t, kCacheSize> last_use_{};
  std::array<Transition, kCacheSize> entries_{};
  std::size_t count_ = 0;
  std::size_t last_hit_ = 0;
  std::uint64_t clock_ = 0;
  std::uint64_t misses_ = 0;
};

}  // namespace netmc::plant
