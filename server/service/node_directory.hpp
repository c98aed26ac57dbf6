#pragma once
// The axis nodes the server has discovered (NodeStatus topic, reliable transient-local), with
// their axes, plant and health. A background thread keeps it current.

#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "dds_types.h"
#include "server/dds/dds_context.hpp"

namespace netmc::service {

struct NodeRecord {
  netmc::dds::NodeStatus status;
  std::chrono::steady_clock::time_point last_seen;
};

class NodeDirectory {
 public:
  explicit NodeDirectory(dds::DdsContext& context);
  ~NodeDirectory();
  NodeDirectory(const NodeDirectory&) = delete;
  NodeDirectory& operator=(const NodeDirectory&) = delete;

  std::vector<NodeRecord> nodes() const;
  // The node hosting `axis_id`, if one was seen within `max_age`.
  std::optional<NodeRecord> node_for_axis(std::uint32_t axis_id,
                                          std::chrono::milliseconds max_age) const;

 private:
  void run();

  dds::SampleReader<netmc::dds::NodeStatus> reader_;
  mutable std::mutex mutex_;
  std::map<std::string, NodeRecord> nodes_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace netmc::service
