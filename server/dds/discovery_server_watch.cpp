#include "server/dds/discovery_server_watch.hpp"

#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>

namespace netmc::dds {

DiscoveryServerWatch::DiscoveryServerWatch(std::vector<std::string> servers, std::vector<std::string> interfaces,
                                           std::chrono::milliseconds bound)
    : servers_(std::move(servers)),
      interfaces_(std::move(interfaces)),
      prefixes_(servers_.size()),
      bound_(bound),
      answered_(servers_.size(), false),
      warned_(servers_.size(), false) {
  for (std::size_t id = 0; id < servers_.size(); ++id) {
    eprosima::fastdds::rtps::get_server_client_default_guidPrefix(static_cast<int>(id), prefixes_[id]);
  }
  thread_ = std::thread([this] { watch(); });
}

DiscoveryServerWatch::~DiscoveryServerWatch() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void DiscoveryServerWatch::discovered(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) {
  std::lock_guard lock(mutex_);
  for (std::size_t id = 0; id < prefixes_.size(); ++id) {
    if (prefixes_[id] != prefix || answered_[id]) continue;
    answered_[id] = true;
    // Said only after a warning: it retracts it.
    if (warned_[id]) {
      const double after = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
      spdlog::info("Fast DDS discovery server {} answered at {} after {:.1f} s", id, servers_[id], after);
    }
  }
  changed_.notify_all();
}

std::string DiscoveryServerWatch::warning(const std::string& address, int id,
                                          const std::vector<std::string>& interfaces,
                                          std::chrono::milliseconds bound) {
  const auto colon = address.rfind(':');
  const std::string host = address.substr(0, colon);
  const std::string port = colon == std::string::npos ? "11811" : address.substr(colon + 1);
  std::string over;
  for (const auto& entry : interfaces) over += (over.empty() ? "" : ",") + entry;
  if (over.empty()) over = "127.0.0.1 (the default)";
  return fmt::format(
      "no Fast DDS discovery server answered at {} within {:g} s: check that it runs (fast-discovery-server -i {} "
      "-l {} -p {}) and that this host reaches it over --interface {}",
      address, std::chrono::duration<double>(bound).count(), id, host, port, over);
}

void DiscoveryServerWatch::watch() {
  std::unique_lock lock(mutex_);
  const bool ended = changed_.wait_for(lock, bound_, [this] {
    return stopping_ || std::all_of(answered_.begin(), answered_.end(), [](bool a) { return a; });
  });
  if (ended) return;
  for (std::size_t id = 0; id < servers_.size(); ++id) {
    if (answered_[id]) continue;
    warned_[id] = true;
    spdlog::warn("{}", warning(servers_[id], static_cast<int>(id), interfaces_, bound_));
  }
}

}  // namespace netmc::dds
