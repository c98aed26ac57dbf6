#pragma once
// `netmc run` (a study on a running netmc-server) and `netmc nodes` (its discovered axis nodes).

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "client/study_runner.hpp"
#include "server/management/management_client.hpp"

namespace netmc::cli {

std::function<int()> add_run_command(CLI::App& app);
std::function<int()> add_nodes_command(CLI::App& app);
// netmc status [JOB]: the server's jobs (state, iterations, what a queued one waits behind).
std::function<int()> add_status_command(CLI::App& app);
// netmc cancel JOB: with the admin token, any job; otherwise the server refuses and says why.
std::function<int()> add_cancel_command(CLI::App& app);

inline constexpr auto kServerConnectTimeout = std::chrono::milliseconds(3000);

// Submits one job and waits for its result; prints each iteration to stderr unless `quiet`;
// `on_iteration` (optional) is called as each iteration arrives. Throws std::runtime_error
// when the server fails the job or stops answering.
RunOutcome run_job_on_server(management::ManagementClient& client, const netmc::v1::JobSpec& spec,
                             std::uint64_t request_id, const std::string& server, bool quiet,
                             const std::function<void()>& on_iteration = {});

}  // namespace netmc::cli
