// Test tool: subscribes to netmc's iteration_log topic on loopback and prints one line per
// sample ("server JOB ITERATION/TOTAL e_sum_m"), until --seconds pass or --expect samples came.

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "dds_typesPubSubTypes.h"
#include "server/dds/dds_context.hpp"
#include "server/dds/topics.hpp"

int main(int argc, char** argv) {
  CLI::App app{"netmc_iteration_log_listener: prints the iteration logs of every server on a domain"};
  int domain = 0;
  double seconds = 60.0;
  int expect = 0;
  app.add_option("--domain", domain)->check(CLI::Range(0, 230));
  app.add_option("--seconds", seconds, "Listen at most this long");
  app.add_option("--expect", expect, "Stop after this many samples");
  std::string security, name = "iteration-log-listener";
  app.add_option("--security", security, "DDS Security directory (scripts/make-lab-pki.sh)");
  app.add_option("--name", name, "Participant name (its certificate's, under --security)");
  CLI11_PARSE(app, argc, argv);
  netmc::dds::DdsOptions options;
  options.domain_id = domain;
  options.transport = netmc::dds::Transport::udp;
  options.name = name;
  options.security_dir = security;
  netmc::dds::DdsContext context(options);
  netmc::dds::SampleReader<netmc::dds::IterationLog> reader(context.reader(
      context.topic<netmc::dds::IterationLogPubSubType>(netmc::dds::kIterationLogTopic), netmc::dds::Delivery::log));
  fmt::print("listening\n");
  std::fflush(stdout);
  const auto end = std::chrono::steady_clock::now() +
                   std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
  int count = 0;
  while (expect == 0 || count < expect) {
    auto log = reader.take_until(end);
    if (!log) break;
    ++count;
    fmt::print("{} {} {}/{} {:.6g}\n", log->server(), log->job_id(), log->iteration(), log->total_iterations(),
               log->e_sum_m());
    std::fflush(stdout);
  }
  return 0;
}
