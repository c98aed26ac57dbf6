#include "server/service/node_directory.hpp"

#include "dds_typesPubSubTypes.h"
#include "server/dds/topics.hpp"

namespace netmc::service {

NodeDirectory::NodeDirectory(dds::DdsContext& context)
    : reader_(context.reader(context.topic<netmc::dds::NodeStatusPubSubType>(dds::kNodeStatusTopic),
                             dds::Delivery::status)),
      thread_([this] { run(); }) {}

NodeDirectory::~NodeDirectory() {
  stop_.store(true);
  thread_.join();
}

void NodeDirectory::run() {
  while (!stop_.load()) {
    if (auto status = reader_.take(std::chrono::milliseconds(100))) {
      std::lock_guard lock(mutex_);
      nodes_[status->node()] = NodeRecord{*status, std::chrono::steady_clock::now()};
    }
  }
}

std::vector<NodeRecord> NodeDirectory::nodes() const {
  std::lock_guard lock(mutex_);
  std::vector<NodeRecord> out;
  for (const auto& [name, record] : nodes_) out.push_back(record);
  return out;
}

std::optional<NodeRecord> NodeDirectory::node_for_axis(std::uint32_t axis_id,
                                                       std::chrono::milliseconds max_age) const {
  std::lock_guard lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  std::optional<NodeRecord> newest;
  for (const auto& [name, record] : nodes_) {
    if (now - record.last_seen > max_age) continue;
    for (const auto id : record.status.axis_ids()) {
      if (id == axis_id && (!newest || record.last_seen > newest->last_seen)) newest = record;
    }
  }
  return newest;
}

}  // namespace netmc::service
