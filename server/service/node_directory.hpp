#pragma once
// The axis nodes the server has discovered (NodeStatus topic, reliable transient-local), with
// their axes, plant and health. A node silent for kNodeExpiry (its status comes every
// kStatusPeriod) or one that said it is leaving is forgotten. An axis belongs to the live node
// that claimed it first; a later claimant is refused (and refuses itself: netmc-axis exits).

#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "dds_types.h"
#include "server/dds/dds_context.hpp"

namespace netmc::service {

// What the node's reports showed an axis do, counted by the server (edges between reports: a
// fault latched, "Quick stop active" entered). Kept while the server runs, a node's leaving
// included, for up to kMaxCountedAxes axes.
struct AxisEventCounts {
  std::uint64_t trips = 0;
  std::uint64_t quick_stops = 0;
};

struct NodeRecord {
  netmc::dds::NodeStatus status;
  std::chrono::steady_clock::time_point first_seen;
  std::chrono::steady_clock::time_point last_seen;
  std::string refused;  // why this node may not serve (an axis held by an older node)
};

class NodeDirectory {
 public:
  explicit NodeDirectory(dds::DdsContext& context,
                         std::chrono::milliseconds expiry = std::chrono::milliseconds(2500));
  ~NodeDirectory();
  NodeDirectory(const NodeDirectory&) = delete;
  NodeDirectory& operator=(const NodeDirectory&) = delete;

  // Live nodes, refused ones included (with the reason).
  std::vector<NodeRecord> nodes() const;
  // The live, unrefused node hosting `axis`, heard from within kFreshStatusPeriods of its status
  // period: a node killed and restarted is listed on until its silence expires, and a job must
  // not start on the dead one's record (its events would come from a participant it does not
  // know); the job waits for the restarted node's own.
  std::optional<NodeRecord> node_for_axis(const std::string& axis) const;
  static constexpr double kFreshStatusPeriods = 2.5;
  std::chrono::milliseconds expiry() const { return expiry_; }
  // The counts of `axis` of node `node` (zero if none was seen).
  AxisEventCounts axis_events(const std::string& node, const std::string& axis) const;
  static constexpr std::size_t kMaxCountedAxes = 1024;

 private:
  void run();
  void expire(std::chrono::steady_clock::time_point now);
  void judge();
  void log_spoof(const std::string& node, const std::string& what);
  // Under mutex_: the edges from `before` (nullptr: a node new to the directory) to `after`.
  void count_axis_events(const netmc::dds::NodeStatus* before, const netmc::dds::NodeStatus& after);

  dds::SampleReader<netmc::dds::NodeStatus> reader_;
  std::chrono::milliseconds expiry_;
  mutable std::mutex mutex_;
  std::map<std::string, NodeRecord> nodes_;
  std::map<std::pair<std::string, std::string>, AxisEventCounts> axis_events_;  // (node, axis)
  std::set<std::string> spoofs_logged_;  // what log_spoof said (each once; the first few)
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace netmc::service
