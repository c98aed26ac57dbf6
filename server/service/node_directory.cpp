#include "server/service/node_directory.hpp"

#include <fmt/ranges.h>
#include <spdlog/spdlog.h>


#include "dds_typesPubSubTypes.h"
#include "server/dds/topics.hpp"

namespace netmc::service {

NodeDirectory::NodeDirectory(dds::DdsContext& context, std::chrono::milliseconds expiry)
    : reader_(context.reader(context.topic<netmc::dds::NodeStatusPubSubType>(dds::kNodeStatusTopic),
                             dds::Delivery::status)),
      expiry_(expiry),
      thread_([this] { run(); }) {}

NodeDirectory::~NodeDirectory() {
  stop_.store(true);
  thread_.join();
}

void NodeDirectory::run() {
  while (!stop_.load()) {
    auto status = reader_.take(std::chrono::milliseconds(100));
    const auto now = std::chrono::steady_clock::now();
    std::lock_guard lock(mutex_);
    // A status is believed only from the participant it names: another participant's word
    // (a spoof of a node's status, its holds or its leaving) is dropped.
    if (status && !dds::sent_by(reader_.last_sender(), status->participant())) {
      log_spoof(status->node(), "names participant " + status->participant().substr(0, 32) + " but " +
                                    dds::prefix_text(reader_.last_sender()) + " sent it");
      status.reset();
    }
    if (status) {
      const std::string name = status->node();
      const auto it = nodes_.find(name);
      // A refused node and a leaving one go; a rival with the same name does not remove the holder.
      const bool same = it != nodes_.end() && it->second.status.participant() == status->participant();
      const bool name_taken = it != nodes_.end() && !same && now - it->second.last_seen <= expiry_;
      if (status->health() == netmc::dds::NODE_REFUSED) {
        spdlog::warn("node {} ({}) {}", name, status->participant(), status->detail());
      }
      if (status->health() == netmc::dds::NODE_LEAVING || status->health() == netmc::dds::NODE_REFUSED) {
        if (same) {
          if (status->health() == netmc::dds::NODE_LEAVING) spdlog::info("node {} left", name);
          nodes_.erase(it);
        }
      } else if (same) {
        count_axis_events(&it->second.status, *status);
        it->second.status = *status;
        it->second.last_seen = now;
      } else if (name_taken) {
        // The live node keeps its name (a node restarted under it is back once the old one is
        // forgotten, as the node itself waits for): an impostor cannot take over its axes.
        log_spoof(name, "participant " + status->participant().substr(0, 32) + " claims the name of live participant " +
                            it->second.status.participant());
      } else {
        spdlog::info("node {} joined: axes {}, plant {}, {} clock, participant {}", name,
                     fmt::join(status->axes(), ","), status->plant(),
                     status->clock(), status->participant());
        count_axis_events(nullptr, *status);
        nodes_[name] = NodeRecord{*status, now, now, ""};  // new, or restarted (a new participant)
      }
    }
    expire(now);
    judge();
  }
}

void NodeDirectory::log_spoof(const std::string& node, const std::string& what) {
  constexpr std::size_t kMaxSpoofsLogged = 16;  // a flood of them cannot fill the log
  const std::string line = "ignored a status of node " + node.substr(0, 64) + ": " + what;
  if (spoofs_logged_.size() >= kMaxSpoofsLogged || !spoofs_logged_.insert(line).second) return;
  spdlog::warn("{}", line);
}

void NodeDirectory::expire(std::chrono::steady_clock::time_point now) {
  for (auto it = nodes_.begin(); it != nodes_.end();) {
    if (now - it->second.last_seen <= expiry_) {
      ++it;
      continue;
    }
    spdlog::warn("node {} lost: silent for {} ms", it->first,
                 std::chrono::duration_cast<std::chrono::milliseconds>(now - it->second.last_seen).count());
    it = nodes_.erase(it);
  }
}

void NodeDirectory::judge() {
  // Each axis belongs to the node that claimed it first; later claimants are refused.
  std::map<std::string, const NodeRecord*> holder;
  for (const auto& [name, record] : nodes_) {
    for (const auto& axis : record.status.axes()) {
      auto& h = holder[axis];
      if (!h || record.first_seen < h->first_seen) h = &record;
    }
  }
  for (auto& [name, record] : nodes_) {
    std::string why;
    for (const auto& axis : record.status.axes()) {
      if (why.empty() && holder[axis] != &record) {
        why = "refused: axis " + axis + " is held by node " + holder[axis]->status.node();
      }
    }
    if (why != record.refused && !why.empty()) {
      spdlog::warn("node {} {}", name, why);
    }
    record.refused = why;
  }
}

void NodeDirectory::count_axis_events(const netmc::dds::NodeStatus* before, const netmc::dds::NodeStatus& after) {
  constexpr const char* kQuickStop = "Quick stop active";
  for (const auto& drive : after.drives()) {
    const netmc::dds::AxisDriveStatus* previous = nullptr;
    if (before) {
      for (const auto& old : before->drives()) {
        if (old.axis() == drive.axis()) previous = &old;
      }
    }
    const bool tripped = drive.fault_latched() && !(previous && previous->fault_latched());
    const bool quick_stop = drive.state() == kQuickStop && !(previous && previous->state() == kQuickStop);
    if (!tripped && !quick_stop) continue;
    const auto key = std::make_pair(after.node(), drive.axis());
    if (!axis_events_.contains(key) && axis_events_.size() >= kMaxCountedAxes) continue;
    auto& counts = axis_events_[key];
    counts.trips += tripped ? 1 : 0;
    counts.quick_stops += quick_stop ? 1 : 0;
  }
}

AxisEventCounts NodeDirectory::axis_events(const std::string& node, const std::string& axis) const {
  std::lock_guard lock(mutex_);
  const auto found = axis_events_.find({node, axis});
  return found == axis_events_.end() ? AxisEventCounts{} : found->second;
}

std::vector<NodeRecord> NodeDirectory::nodes() const {
  std::lock_guard lock(mutex_);
  std::vector<NodeRecord> out;
  const auto now = std::chrono::steady_clock::now();
  for (const auto& [name, record] : nodes_) {
    if (now - record.last_seen <= expiry_) out.push_back(record);
  }
  return out;
}

std::optional<NodeRecord> NodeDirectory::node_for_axis(const std::string& axis) const {
  std::lock_guard lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  for (const auto& [name, record] : nodes_) {
    const double period_s = record.status.status_period_s() > 0.0 ? record.status.status_period_s() : 0.5;
    const auto fresh = std::chrono::duration<double>(kFreshStatusPeriods * period_s);
    if (now - record.last_seen > expiry_ || now - record.last_seen > fresh || !record.refused.empty()) continue;
    for (const auto& a : record.status.axes()) {
      if (a == axis) return record;
    }
  }
  return std::nullopt;
}

}  // namespace netmc::service
