// netmc sweep --server: the configurations go to a management endpoint one after another.
// Here the endpoint runs each job in-process (as netmc-server's lockstep mode equals sim), so
// the CSV must equal the in-process sweep's byte for byte.
#include <utility>  // before Asio: Boost 1.74 needs it

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "tests/client/netmc_in_process.hpp"
#include "server/job/job_builder.hpp"
#include "server/management/management_server.hpp"
#include "server/sim/contour_job_runner.hpp"

namespace netmc::cli {
namespace {

namespace fs = std::filesystem;

int netmc(const std::vector<std::string>& arguments) { return run_netmc_captured(arguments).exit_code; }

std::string read(const fs::path& path) {
  std::ifstream file(path);
  std::ostringstream content;
  content << file.rdbuf();
  return content.str();
}

TEST(SweepOnServer, SameCsvAsInProcess) {
  boost::asio::io_context io;
  std::uint64_t jobs = 0;
  management::ManagementServer server(io, "127.0.0.1", 0, {[&](management::Session& session,
                                                              const netmc::v1::Request& request) {
    const auto& spec = request.submit().spec();
    const std::uint64_t job_id = ++jobs;
    netmc::v1::Response accepted;
    accepted.set_request_id(request.request_id());
    accepted.mutable_accepted()->set_job_id(job_id);
    session.send(accepted);
    sim::ContourJobRunner runner(job::build_contour_job(spec));
    netmc::v1::Response finished;
    finished.set_request_id(request.request_id());
    auto& result = *finished.mutable_finished()->mutable_result();
    result = job::describe_run(spec, runner.controller_description());
    runner.run_all([&](const sim::IterationRecord& record) {
      *result.add_iterations() = job::to_proto(record.metrics);
      netmc::v1::Response update;
      update.set_request_id(request.request_id());
      update.mutable_iteration()->set_job_id(job_id);
      update.mutable_iteration()->set_total_iterations(spec.iterations());
      *update.mutable_iteration()->mutable_metrics() = job::to_proto(record.metrics);
      session.send(update);
    });
    finished.mutable_finished()->set_job_id(job_id);
    finished.mutable_finished()->set_state("done");
    session.send(finished);
  }});
  std::thread io_thread([&] { io.run(); });

  const auto dir = fs::temp_directory_path() / "netmc_sweep_server_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::vector<std::string> grid{"sweep", "--controller", "adrc,adrc+pidccc", "--delay-max", "1ms,6ms",
                                      "--seeds", "1..2", "--iterations", "2", "--duration", "0.5s", "-q"};
  auto on_server = grid;
  on_server.insert(on_server.end(), {"--server", "127.0.0.1:" + std::to_string(server.port()), "--csv",
                                     (dir / "server.csv").string()});
  auto in_process = grid;
  in_process.insert(in_process.end(), {"--csv", (dir / "local.csv").string()});
  EXPECT_EQ(netmc(on_server), 0);
  EXPECT_EQ(netmc(in_process), 0);
  server.stop();
  io.stop();
  io_thread.join();

  EXPECT_EQ(jobs, 8u);
  const std::string local = read(dir / "local.csv");
  EXPECT_GT(std::count(local.begin(), local.end(), '\n'), 8);
  EXPECT_EQ(read(dir / "server.csv"), local);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace netmc::cli
