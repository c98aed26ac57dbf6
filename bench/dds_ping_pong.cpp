// Bare Fast DDS ping-pong with netmc's own sample types and realtime QoS (best-effort): the
// reference for the closed loop's feedback-to-setpoint round trip. One process pongs, one pings.
// Run: bench/realtime_sweep.sh BUILD_DIR (starts a pong and a ping beside each closed-loop run).

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <thread>
#include <vector>

#include "dds_typesPubSubTypes.h"
#include "server/dds/dds_context.hpp"
#include "server/realtime/realtime_options_cli.hpp"

namespace {

using Clock = std::chrono::steady_clock;

int pong(netmc::dds::DdsContext& context, double seconds) {
  auto* writer = context.writer(context.topic<netmc::dds::SetpointPubSubType>("bench/pong"),
                                netmc::dds::Delivery::stream);
  netmc::dds::SampleReader<netmc::dds::Feedback> reader(context.reader(
      context.topic<netmc::dds::FeedbackPubSubType>("bench/ping"), netmc::dds::Delivery::stream));
  netmc::realtime::tighten_timer_slack();
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  netmc::dds::Setpoint reply;
  while (Clock::now() < end) {
    if (auto ping = reader.take(std::chrono::milliseconds(100))) {
      reply.axis(ping->axis());
      reply.cycle(ping->cycle());
      reply.command(ping->position_m());
      writer->write(&reply);
    }
  }
  return 0;
}

int ping(netmc::dds::DdsContext& context, int rate_hz, int count) {
  auto* writer = context.writer(context.topic<netmc::dds::FeedbackPubSubType>("bench/ping"),
                                netmc::dds::Delivery::stream);
  netmc::dds::SampleReader<netmc::dds::Setpoint> reader(context.reader(
      context.topic<netmc::dds::SetpointPubSubType>("bench/pong"), netmc::dds::Delivery::stream));
  if (!netmc::dds::wait_for_readers(writer, 1, std::chrono::seconds(10))) {
    fmt::print(stderr, "ping: no pong matched within 10 s\n");
    return 1;
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let the reverse path match
  // Same shape as an axis's feedback: one applied setpoint.
  netmc::dds::Feedback sample;
  sample.kind(netmc::dds::FEEDBACK_SAMPLE);
  sample.applied().resize(1);
  netmc::realtime::tighten_timer_slack();
  std::vector<double> rtt_us;
  const auto period = std::chrono::nanoseconds(1'000'000'000 / rate_hz);
  auto next = Clock::now();
  for (int i = 0; i < count; ++i) {
    next += period;
    std::this_thread::sleep_until(next);
    sample.cycle(static_cast<std::uint64_t>(i));
    const auto sent = Clock::now();
    writer->write(&sample);
    while (auto reply = reader.take(std::chrono::milliseconds(200))) {
      if (reply->cycle() == static_cast<std::uint64_t>(i)) {
        rtt_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - sent).count());
        break;
      }
    }
  }
  if (rtt_us.empty()) return 1;
  std::sort(rtt_us.begin(), rtt_us.end());
  const auto at = [&](double q) { return rtt_us[std::min(rtt_us.size() - 1, static_cast<std::size_t>(q * static_cast<double>(rtt_us.size())))]; };
  fmt::print("bare Fast DDS ping-pong at {} Hz: {} of {} answered, round trip p50 {:.0f} us, p99 {:.0f} us, max {:.0f} us\n",
             rate_hz, rtt_us.size(), count, at(0.50), at(0.99), rtt_us.back());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"netmc_dds_ping_pong: bare Fast DDS round trip with netmc's types and QoS"};
  std::string role = "ping";
  int rate = 1000, count = 5000, domain = 0;
  double seconds = 30.0;
  app.add_option("--role", role)->check(CLI::IsMember({"ping", "pong"}));
  app.add_option("--rate", rate, "Pings per second")->check(CLI::Range(1, 100000));
  app.add_option("--count", count)->check(CLI::Range(1, 10000000));
  app.add_option("--seconds", seconds, "How long pong serves");
  app.add_option("--domain", domain);
  netmc::realtime::RealtimeScheduling scheduling;
  netmc::realtime::add_realtime_options(app, scheduling);  // the same as the closed loop's processes
  CLI11_PARSE(app, argc, argv);
  for (const auto& fallback : netmc::realtime::apply_process_scheduling(scheduling).fallbacks) {
    fmt::print(stderr, "netmc_dds_ping_pong: warning: {}\n", fallback);
  }
  netmc::dds::DdsOptions options;
  options.domain_id = domain;
  options.transport = netmc::dds::Transport::udp;
  options.name = "bench-" + role;
  netmc::dds::DdsContext context(options);
  return role == "pong" ? pong(context, seconds) : ping(context, rate, count);
}
