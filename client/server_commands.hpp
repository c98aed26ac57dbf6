#pragma once
// The commands that talk to a running netmc-server: run, submit, watch, nodes, reset, status, cancel.

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "client/study_runner.hpp"
#include "server/management/management_client.hpp"

namespace netmc::cli {

std::function<int()> add_run_command(CLI::App& app);
// netmc submit: the jobs of a study queued, kept when this client leaves; prints their ids.
std::function<int()> add_submit_command(CLI::App& app);
// netmc watch JOB: a job's iterations and result, from any connection.
std::function<int()> add_watch_command(CLI::App& app);
// netmc nodes: the server's axis nodes, each axis with its drive, CiA 402 state and last fault.
std::function<int()> add_nodes_command(CLI::App& app);
// netmc reset NODE: the operator's reset of a node's latched axis faults (admin token).
std::function<int()> add_reset_command(CLI::App& app);
// netmc status [JOB]: the server's jobs (state, iterations, what a queued one waits behind).
std::function<int()> add_status_command(CLI::App& app);
// netmc cancel JOB: with the admin token, any job; otherwise the server refuses and says why.
std::function<int()> add_cancel_command(CLI::App& app);
// netmc jobs: the server's job history (its job store with --state-dir), with filters.
std::function<int()> add_jobs_command(CLI::App& app);

inline constexpr auto kServerConnectTimeout = std::chrono::milliseconds(3000);

// One request (request id 1, filled in by `fill`) on a connection of its own, and its answer;
// throws std::runtime_error naming the server for an error answer or none within 10 s.
netmc::v1::Response ask_server(const std::string& server, const std::function<void(netmc::v1::Request&)>& fill);
// --server HOST:PORT (or $NETMC_SERVER) of the commands that talk to a netmc-server.
void add_server_option(CLI::App* command, std::string& server);

// Submits one job and waits for its result; prints each iteration to stderr unless `quiet`;
// `on_iteration` (optional) is called as each iteration arrives. Throws std::runtime_error
// when the server fails the job or stops answering.
RunOutcome run_job_on_server(management::ManagementClient& client, const netmc::v1::JobSpec& spec,
                             std::uint64_t request_id, const std::string& server, bool quiet,
                             const std::function<void()>& on_iteration = {});

}  // namespace netmc::cli
