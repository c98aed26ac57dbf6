#pragma once
// Warns when a Fast DDS Discovery Server a participant was given never answers: without one the
// participant finds no other and would otherwise say nothing; see docs/architecture.md.

#include <fastdds/rtps/common/GuidPrefix_t.hpp>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace netmc::dds {

// A running server answers a client's first announcement within milliseconds, and an unanswered
// client announces itself again about every 0.5 s (Fast DDS's client sync period): 5 s is ten
// tries, enough for a server started a moment after the process, and short enough that the
// warning shows while whoever started the process still looks at it.
inline constexpr std::chrono::seconds kDiscoveryServerAnswerBound{5};

class DiscoveryServerWatch {
 public:
  // `servers`: the --discovery-server addresses, the i-th being the server with id i (its GUID
  // prefix Fast DDS's default for that id); `interfaces`: --interface as given (empty: default).
  DiscoveryServerWatch(std::vector<std::string> servers, std::vector<std::string> interfaces,
                       std::chrono::milliseconds bound = kDiscoveryServerAnswerBound);
  ~DiscoveryServerWatch();
  DiscoveryServerWatch(const DiscoveryServerWatch&) = delete;
  DiscoveryServerWatch& operator=(const DiscoveryServerWatch&) = delete;

  // Called for every participant discovery announces (the participant listener's thread).
  void discovered(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix);

  // The warning for server `id` at `address`, as the log shows it.
  static std::string warning(const std::string& address, int id, const std::vector<std::string>& interfaces,
                             std::chrono::milliseconds bound);

 private:
  void watch();

  std::vector<std::string> servers_;
  std::vector<std::string> interfaces_;
  std::vector<eprosima::fastrtps::rtps::GuidPrefix_t> prefixes_;
  std::chrono::milliseconds bound_;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<bool> answered_;
  std::vector<bool> warned_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace netmc::dds
