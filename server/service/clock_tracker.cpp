#include "server/service/clock_tracker.hpp"

#include <set>

#include "dds_typesPubSubTypes.h"
#include "server/dds/topics.hpp"

namespace netmc::service {

ClockTracker::ClockTracker(dds::DdsContext& context, const NodeDirectory& nodes, dds::TimeBase base)
    : nodes_(nodes),
      base_(base),
      server_(context.identity()),
      probes_(context.writer(context.topic<netmc::dds::ClockProbePubSubType>(dds::kClockProbeTopic),
                             dds::Delivery::stream)),
      replies_(context.reader(context.topic<netmc::dds::ClockReplyPubSubType>(dds::kClockReplyTopic),
                              dds::Delivery::stream)),
      thread_([this] { run(); }) {}

ClockTracker::~ClockTracker() {
  stop_.store(true);
  thread_.join();
}

std::optional<netsim::ClockOffsetEstimate> ClockTracker::estimate(const std::string& node,
                                                                  std::size_t min_exchanges) const {
  std::lock_guard lock(mutex_);
  const auto it = tracked_.find(node);
  if (it == tracked_.end()) return std::nullopt;
  auto e = it->second.estimator.estimate();
  if (!e || e->exchanges < min_exchanges) return std::nullopt;
  return e;
}

void ClockTracker::run() {
  std::uint64_t sequence = 0;
  auto next_probe = std::chrono::steady_clock::now();
  while (!stop_.load()) {
    if (std::chrono::steady_clock::now() >= next_probe) {
      next_probe += kProbePeriod;
      std::set<std::string> live;
      for (const auto& record : nodes_.nodes()) {
        const std::string name = record.status.node();
        live.insert(name);
        {
          std::lock_guard lock(mutex_);
          auto& tracked = tracked_[name];
          if (tracked.participant != record.status.participant()) {
            tracked.participant = record.status.participant();  // restarted: a new clock
            tracked.estimator.reset();
          }
        }
        netmc::dds::ClockProbe probe;
        probe.node(name);
        probe.server(server_);
        probe.number(++sequence);
        probe.t1_s(now_s());
        try {
          dds::write_checked(probes_, &probe);
        } catch (const std::exception&) {
          // A probe that cannot leave is a lost one; the next period tries again.
        }
      }
      std::lock_guard lock(mutex_);
      for (auto it = tracked_.begin(); it != tracked_.end();) {
        it = live.count(it->first) ? std::next(it) : tracked_.erase(it);
      }
    }
    auto received = replies_.take_until_received(
        std::min(next_probe, std::chrono::steady_clock::now() + std::chrono::milliseconds(50)));
    if (!received) continue;
    const auto& reply = received->first;
    const double t4 = dds::time_base_at_s(base_, received->second);
    if (reply.server() != server_) continue;  // another server's probe
    std::lock_guard lock(mutex_);
    const auto it = tracked_.find(reply.node());
    // Only the node's own reply measures its clock: a forged one would shift a realtime job's start.
    if (it == tracked_.end() || !dds::sent_by(replies_.last_sender(), it->second.participant)) continue;
    it->second.estimator.add({reply.t1_s(), reply.t2_s(), reply.t3_s(), t4});
  }
}

}  // namespace netmc::service
