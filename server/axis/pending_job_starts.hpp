#pragma once
// Jobs whose start waits for their server. A node starts an axis's job only once it and the job's
// server are matched both ways (AxisNodeLink::linked_to_server); that wait is looked at by the
// node's loop on each pass, never slept in, so a participant that begins a job and never reads
// (forged, or a server that died) holds up nothing but the axis it named: the node's other axes
// keep sampling and its watchdog keeps watching.
// The axis's later job control waits behind its start, in order.

#include <chrono>
#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "dds_types.h"

namespace netmc::axis {

class PendingJobStarts {
 public:
  using Clock = std::chrono::steady_clock;
  // How long a start may wait to be linked to its server once the server began a job.
  static constexpr std::chrono::milliseconds kLinkTimeout{5000};
  // How often the loop looks while a start waits.
  static constexpr std::chrono::milliseconds kLookPeriod{2};
  // Later control kept per waiting axis; beyond it the oldest is dropped (a flood of control
  // for one axis cannot grow the node).
  static constexpr std::size_t kMaxHeldBack = 32;
  // Of those, at most one carries a job spec (up to 4 MiB each): a server begins one job at a time
  // on an axis, so a second spec behind a waiting start is a peer's, and the older one goes. A
  // waiting axis then holds at most two specs, however many begins a peer sends.
  static constexpr std::size_t kMaxHeldBackSpecs = 1;

  // The start `begin` waits until it is linked to its server. Only for an axis that does not wait
  // yet: a waiting axis's control is held back (hold_back), its start included.
  void wait(const netmc::dds::JobControl& begin, Clock::time_point now);
  bool waiting(const std::string& axis) const { return waiting_.count(axis) > 0; }
  bool empty() const { return waiting_.empty(); }
  // Control for a waiting axis: replayed after its start is settled.
  void hold_back(const netmc::dds::JobControl& control);

  struct Settled {
    netmc::dds::JobControl begin;
    bool linked = false;  // else: its time is over
    std::vector<netmc::dds::JobControl> held_back;
  };
  // The starts linked now, or whose time is over; the others keep waiting.
  std::vector<Settled> settle(const std::function<bool(const netmc::dds::JobControl&)>& linked,
                              Clock::time_point now);

 private:
  struct Waiting {
    netmc::dds::JobControl begin;
    Clock::time_point deadline;
    std::vector<netmc::dds::JobControl> held_back;
  };
  std::map<std::string, Waiting> waiting_;  // by axis
};

}  // namespace netmc::axis
