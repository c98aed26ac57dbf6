#include "client/server_commands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <iostream>
#include <map>
#include <optional>
#include <stdexcept>
#include <thread>

#include "client/job_token_store.hpp"
#include "client/realtime_study_length.hpp"
#include "client/study_flags.hpp"
#include "client/study_report.hpp"
#include "client/verbosity.hpp"
#include "idl/management.pb.h"
#include "server/drive/cia402.hpp"
#include "server/job/job_builder.hpp"
#include "server/management/access_token.hpp"
#include "server/management/management_client.hpp"
#include "server/store/job_list.hpp"

namespace netmc::cli {
namespace {

// Waits for the response to `request_id`, skipping nothing: the server answers in order.
netmc::v1::Response expect_response(management::ManagementClient& client,
                                    std::chrono::milliseconds timeout,
                                    const std::string& server) {
  auto response = client.receive(timeout);
  if (!response) throw std::runtime_error("server " + server + ": no answer within " +
                                          std::to_string(timeout.count()) + " ms");
  if (response->has_error()) throw std::runtime_error("server " + server + ": " + response->error().message());
  return *response;
}

}  // namespace

// One request (request id 1, filled in by `fill`) on a connection of its own, and its answer.
netmc::v1::Response ask_server(const std::string& server, const std::function<void(netmc::v1::Request&)>& fill) {
  management::ManagementClient client(server, kServerConnectTimeout);
  netmc::v1::Request request;
  request.set_request_id(1);
  fill(request);
  client.send(request);
  return expect_response(client, std::chrono::seconds(10), server);
}

// --server HOST:PORT (or $NETMC_SERVER) of the commands that talk to a netmc-server.
void add_server_option(CLI::App* command, std::string& server) {
  command->add_option("--server", server, "netmc-server management endpoint HOST:PORT")->envname("NETMC_SERVER");
}


namespace {

void print_iteration(const std::string& label, const netmc::v1::IterationUpdate& update) {
  const auto& m = update.metrics();
  std::cerr << fmt::format(
      "  [{}] iteration {}/{}  e_max {:.4f} mm  e_sum {:.3f} mm  tau mean/p99/max {:.3f}/{:.3f}/{:.3f} ms"
      " (sc {:.3f}, cc {:.3f}, ca {:.3f} ms mean{}){}{}\n",
      label, m.iteration(), update.total_iterations(), m.e_max_m() * 1e3, m.e_sum_m() * 1e3, m.tau_mean_s() * 1e3,
      m.tau_p99_s() * 1e3, m.tau_max_s() * 1e3, m.tau_sc_mean_s() * 1e3, m.tau_cc_mean_s() * 1e3,
      m.tau_ca_mean_s() * 1e3,
      // Realtime across clocks: the split into sc and ca is good to +- half a round trip.
      m.clock_uncertainty_s() > 0.0 ? fmt::format(", clocks +-{:.3f} ms", m.clock_uncertainty_s() * 1e3) : "",
      m.lost_feedback() + m.lost_setpoints() > 0
          ? fmt::format("  lost feedback {} setpoints {}", m.lost_feedback(), m.lost_setpoints())
          : "",
      m.deadline_misses() > 0 ? fmt::format("  deadline misses {} (late feedback {})", m.deadline_misses(),
                                            m.late_feedback())
                              : "");
}

// A followed job's end: its result (for a job that did not end done, the iterations it kept) and,
// unless it ended done, why not.
struct FollowedJob {
  RunOutcome outcome;
  std::string failure;
};

// Reads a job's iterations, then its end, from `client` (the answers to a submit or a watch);
// `silence_limit`: how long the server may say nothing before the job is given up (none: as long
// as the connection lasts).
FollowedJob follow_job(management::ManagementClient& client, std::uint64_t job_id, const std::string& label,
                       const std::string& server, bool quiet, std::optional<std::chrono::milliseconds> silence_limit,
                       const std::function<void()>& on_iteration) {
  while (true) {
    std::optional<netmc::v1::Response> response;
    do {
      response = client.receive(silence_limit.value_or(std::chrono::hours(1)));
    } while (!response && !silence_limit);
    if (!response) {
      throw std::runtime_error("server " + server + ": no answer within " +
                               std::to_string(silence_limit->count()) + " ms");
    }
    if (response->has_error()) throw std::runtime_error("server " + server + ": " + response->error().message());
    if (response->has_iteration()) {
      if (on_iteration) on_iteration();
      if (!quiet) print_iteration(label, response->iteration());
    } else if (response->has_finished()) {
      const auto& finished = response->finished();
      // An ended job cannot be cancelled: the token netmc submit saved for it is needed no more.
      forget_job_token(server, job_id);
      FollowedJob followed;
      followed.outcome.result = finished.result();
      if (finished.state() != "done") {
        followed.failure = fmt::format("job {} ({}) {}: {}", job_id, label, finished.state(), finished.error());
      } else if (followed.outcome.result.iterations_size() == 0) {
        followed.failure = fmt::format("job {} ({}) finished without iterations", job_id, label);
      }
      return followed;
    }
  }
}

// Sends one job; returns its id and cancel token once the server has accepted it.
netmc::v1::JobAccepted submit_job(management::ManagementClient& client, const netmc::v1::JobSpec& spec,
                                  std::uint64_t request_id, const std::string& server, bool keep_after_disconnect) {
  netmc::v1::Request request;
  request.set_request_id(request_id);
  *request.mutable_submit()->mutable_spec() = spec;
  request.mutable_submit()->set_keep_after_disconnect(keep_after_disconnect);
  // The server reads no file a client names: delay traces travel inside the spec.
  job::inline_delay_traces(*request.mutable_submit()->mutable_spec());
  client.send(request);
  const auto accepted = expect_response(client, std::chrono::seconds(30), server);
  if (!accepted.has_accepted()) throw std::runtime_error("server " + server + ": unexpected answer to submit");
  return accepted.accepted();
}

std::string job_label(const netmc::v1::JobSpec& spec) {
  return spec.name().empty() ? spec.controller().name() : spec.name();
}

}  // namespace

RunOutcome run_job_on_server(management::ManagementClient& client, const netmc::v1::JobSpec& spec,
                             std::uint64_t request_id, const std::string& server, bool quiet,
                             const std::function<void()>& on_iteration) {
  const std::uint64_t job_id = submit_job(client, spec, request_id, server, false).job_id();
  const std::string label = job_label(spec);
  if (!quiet) std::cerr << fmt::format("job {} ({}) accepted by {}\n", job_id, label, server);
  // An iteration takes seconds in realtime and milliseconds in lockstep; nodes may need
  // discovery time first.
  auto followed = follow_job(client, job_id, label, server, quiet, std::chrono::seconds(120), on_iteration);
  if (!followed.failure.empty()) throw std::runtime_error(followed.failure);
  return std::move(followed.outcome);
}

std::function<int()> add_run_command(CLI::App& app) {
  struct Flags {
    StudyFlags study;
    std::string server = "127.0.0.1:7300";
    FailOnUnstable fail_on_unstable;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* run = app.add_subcommand(
      "run", "Run a study on a netmc-server and its axis nodes (same flags and presets as sim)");
  add_server_option(run, flags->server);
  add_study_flags(run, flags->study);
  flags->fail_on_unstable.add_flag(run);
  return [flags]() -> int {
    const StudyPlan plan = plan_from_flags(flags->study);
    if (!flags->study.json_path.empty()) check_output_path(flags->study.json_path, "--json");
    std::ostream& report = is_standard_output(flags->study.json_path) ? std::cerr : std::cout;
    if (const auto notice = realtime_study_notice(plan.jobs); notice && !verbosity().quiet) {
      std::cerr << *notice << '\n';
    }
    management::ManagementClient client(flags->server, kServerConnectTimeout);
    std::vector<RunOutcome> outcomes;
    std::uint64_t request_id = 1;
    for (const auto& spec : plan.jobs) {
      outcomes.push_back(run_job_on_server(client, spec, request_id++, flags->server,
                                           verbosity().quiet));
    }
    if (!flags->study.json_path.empty()) write_output(flags->study.json_path, study_json(outcomes));
    print_study_table(report, plan, outcomes);
    if (flags->study.curve) print_learning_curve(report, outcomes);
    return flags->fail_on_unstable.exit_code(outcomes);
  };
}

std::function<int()> add_submit_command(CLI::App& app) {
  struct Flags {
    StudyFlags study;
    std::string server = "127.0.0.1:7300";
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* submit = app.add_subcommand(
      "submit", "Queue a study's jobs on a netmc-server and return at once: they run on without this client "
                "(same flags and presets as run); prints one job id per line; follow a job with netmc watch");
  add_server_option(submit, flags->server);
  add_study_flags(submit, flags->study);
  // Results go to whoever watches the job.
  for (const char* name : {"--json", "--curve"}) submit->remove_option(submit->get_option(name));
  return [flags]() -> int {
    const StudyPlan plan = plan_from_flags(flags->study);
    // Every job is checked before the first is sent: a bad one leaves nothing queued.
    // The server and its nodes open plugin and FMU files (their own copies): not checked here.
    for (const auto& spec : plan.jobs) job::build_contour_job(spec, job::check_without_files());
    management::ManagementClient client(flags->server, kServerConnectTimeout);
    std::uint64_t request_id = 1;
    for (const auto& spec : plan.jobs) {
      const auto accepted = submit_job(client, spec, request_id++, flags->server, true);
      const std::uint64_t job_id = accepted.job_id();
      fmt::print("{}\n", job_id);
      std::fflush(stdout);
      // The job is queued whether or not its token can be kept: say so, and go on.
      std::string token_note;
      try {
        if (!accepted.cancel_token().empty()) {
          token_note = "; cancel it from any terminal with: netmc cancel " + std::to_string(job_id) + " (its token: " +
                       save_job_token(flags->server, job_id, accepted.cancel_token()).string() + ")";
        }
      } catch (const std::exception& error) {
        std::cerr << fmt::format("job {}: its cancel token was not saved: {}\n", job_id, error.what());
      }
      if (!verbosity().quiet) {
        std::cerr << fmt::format("job {} ({}) queued on {}; follow it with: netmc watch {}{}\n", job_id,
                                 job_label(spec), flags->server, job_id, token_note);
      }
    }
    return 0;
  };
}

std::function<int()> add_watch_command(CLI::App& app) {
  struct Flags {
    std::string server = "127.0.0.1:7300";
    std::uint64_t job = 0;
    std::string json_path;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* watch = app.add_subcommand(
      "watch", "Follow a job of a netmc-server from any connection: its iterations (the earlier ones first) "
               "until it ends, then its table; the job runs on if this client stops");
  watch->add_option("JOB", flags->job, "The job's id (as netmc submit, run or status print it)")
      ->required()
      ->check(CLI::PositiveNumber);
  add_server_option(watch, flags->server);
  watch->add_option("--json", flags->json_path,
                    "Write the job's result as JSON (as netmc run --json writes it; - for standard output)");
  return [flags]() -> int {
    if (!flags->json_path.empty()) check_output_path(flags->json_path, "--json");
    std::ostream& report = is_standard_output(flags->json_path) ? std::cerr : std::cout;
    management::ManagementClient client(flags->server, kServerConnectTimeout);
    netmc::v1::Request request;
    request.set_request_id(1);
    request.mutable_watch()->set_job_id(flags->job);
    client.send(request);
    const auto first = expect_response(client, std::chrono::seconds(10), flags->server);
    if (!first.has_status() || first.status().jobs_size() != 1) {
      throw std::runtime_error("server " + flags->server + ": unexpected answer to watch");
    }
    const auto& status = first.status().jobs(0);
    if (!verbosity().quiet) {
      std::cerr << fmt::format("job {} ({}) on {}: {}, {}/{} iterations{}\n", flags->job, status.label(),
                               flags->server, status.state(), status.iterations_done(), status.iterations_total(),
                               status.waiting_for().empty() ? "" : ", waits for " + status.waiting_for());
    }
    // A queued job may wait behind long ones: the watch lasts as long as the connection.
    auto followed = follow_job(client, flags->job, status.label(), flags->server, verbosity().quiet, std::nullopt, {});
    // A job that failed or was cancelled: its kept iterations are written and shown all the same.
    if (followed.outcome.result.iterations_size() == 0) throw std::runtime_error(followed.failure);
    std::vector<RunOutcome> outcomes{std::move(followed.outcome)};
    if (!flags->json_path.empty()) write_output(flags->json_path, study_json(outcomes));
    StudyPlan plan;
    plan.title = fmt::format("job {} on {}", flags->job, flags->server);
    // netmc run's table: the steady-window one only where the runs had a steady window (the
    // presets that ask for it set their evaluation start inside the iteration).
    plan.steady_metrics = std::any_of(outcomes.front().result.iterations().begin(),
                                      outcomes.front().result.iterations().end(),
                                      [](const auto& m) { return m.has_e_rms_steady_m(); });
    print_study_table(report, plan, outcomes);
    if (!followed.failure.empty()) throw std::runtime_error(followed.failure + " (its " +
                                                            std::to_string(outcomes.front().result.iterations_size()) +
                                                            " kept iterations are above" +
                                                            (flags->json_path.empty() ? "" : " and in " + flags->json_path) + ")");
    return 0;
  };
}

namespace {

// netmc nodes's table: a line per node, then a line per axis with its drive and CiA 402 state.
void print_nodes(const netmc::v1::NodesReply& reply) {
  fmt::print("{:<20} {:<10} {:<10} {:<9} {:>8} {:>18} {:>9}  {}\n", "node", "axes", "plant", "clock",
             "seen [s]", "offset [s]", "rtt [ms]", "health");
  for (const auto& node : reply.nodes()) {
    std::string axes;
    for (const auto& axis : node.axes()) axes += (axes.empty() ? "" : ",") + axis;
    const std::string offset = node.clock_measured() ? fmt::format("{:+.6f}", node.clock_offset_s()) : "-";
    const std::string rtt = node.clock_measured() ? fmt::format("{:.3f}", node.round_trip_s() * 1e3) : "-";
    fmt::print("{:<20} {:<10} {:<10} {:<9} {:>8.1f} {:>18} {:>9}  {}{}{}\n", node.node(), axes, node.plant(),
               node.clock(), node.last_seen_s(), offset, rtt, node.health(),
               node.held_by().empty() ? "" : " (held by " + node.held_by() + ")",
               node.server_name().empty() ? "" : " (obeys " + node.server_name() + ")");
    for (const auto& drive : node.drives()) {
      // A hardware axis's motion and position (a simulated one moves only in a job's time).
      const bool hardware = drive.motion() != "off" || drive.position_m() != 0.0;
      fmt::print("  axis {:<12} {:<34} {:<22}{} error {}{}{}\n", drive.axis(), drive.drive(), drive.state(),
                 hardware ? fmt::format(" {} at {:.6f} m", drive.motion(), drive.position_m()) : "",
                 drive::describe_error_code(static_cast<std::uint16_t>(drive.error_code())),
                 drive.fault_latched() ? "  FAULT: " + drive.last_fault()
                 : drive.last_fault().empty() ? ""
                                              : "  last fault: " + drive.last_fault(),
                 drive.limits().empty() ? "" : "  limits " + drive.limits());
    }
  }
  if (reply.nodes_size() == 0) fmt::print("(no axis node discovered)\n");
}

}  // namespace

std::function<int()> add_nodes_command(CLI::App& app) {
  struct Flags {
    std::string server = "127.0.0.1:7300";
    bool json = false;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* nodes = app.add_subcommand(
      "nodes", "List the axis nodes a netmc-server has discovered, with each axis's drive, CiA 402 state and last fault "
               "(seen [s]: seconds since the node's last status; a node reports every 0.5 s and is dropped after 2.5 s "
               "of silence)");
  add_server_option(nodes, flags->server);
  nodes->add_flag("--json", flags->json,
                  "Print the reply as JSON (protobuf JSON mapping of netmc.v1.NodesReply), for scripts");
  return [flags]() -> int {
    const auto response = ask_server(flags->server, [](netmc::v1::Request& request) { request.mutable_nodes(); });
    if (flags->json) {
      fmt::print("{}\n", job::to_json(response.nodes()));
      return 0;
    }
    print_nodes(response.nodes());
    return 0;
  };
}

std::function<int()> add_reset_command(CLI::App& app) {
  struct Flags {
    std::string server = "127.0.0.1:7300";
    std::string node;
    std::vector<std::string> axes;
    int wait_ms = 5000;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* reset = app.add_subcommand(
      "reset", "Reset the latched faults of a node's axes (CiA 402 fault reset), through the server; needs the "
               "server's admin token where it has one (NETMC_TOKEN_FILE naming the file of netmc-server "
               "--admin-token-file). Waits until the node reports the axes out of Fault.");
  reset->add_option("NODE", flags->node, "The node's name (netmc nodes lists them)")->required();
  reset->add_option("--axis", flags->axes, "Only this axis (repeatable; default: every axis of the node)");
  add_server_option(reset, flags->server);
  reset->add_option("--wait", flags->wait_ms, "Milliseconds to wait for the node to report the reset")
      ->check(CLI::Range(0, 60000));
  return [flags]() -> int {
    ask_server(flags->server, [&](netmc::v1::Request& request) {
      auto& asked = *request.mutable_reset();
      asked.set_node(flags->node);
      for (const auto& axis : flags->axes) asked.add_axes(axis);
    });
    // The node answers on its status: poll the server's view until no asked axis is in fault.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(flags->wait_ms);
    while (true) {
      const auto reply = ask_server(flags->server, [](netmc::v1::Request& request) { request.mutable_nodes(); }).nodes();
      std::vector<std::string> still;
      const netmc::v1::NodeInfo* node = nullptr;
      for (const auto& candidate : reply.nodes()) {
        if (candidate.node() == flags->node) node = &candidate;
      }
      if (node) {
        for (const auto& drive : node->drives()) {
          const bool asked = flags->axes.empty() ||
                             std::find(flags->axes.begin(), flags->axes.end(), drive.axis()) != flags->axes.end();
          if (asked && (drive.fault_latched() || drive.state() == "Fault" || drive.state() == "no answer")) {
            still.push_back(drive.axis());
          }
        }
      }
      if (node && still.empty()) {
        netmc::v1::NodesReply shown;
        *shown.add_nodes() = *node;
        print_nodes(shown);
        return 0;
      }
      if (std::chrono::steady_clock::now() >= deadline) {
        std::string names;
        for (const auto& axis : still) names += (names.empty() ? "" : ", ") + axis;
        throw std::runtime_error(node ? "reset: node " + flags->node + " still reports axis " + names +
                                            " in fault after " + std::to_string(flags->wait_ms) + " ms: " +
                                            node->health() + ""
                                      : "reset: node " + flags->node + " is no longer listed by the server");
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  };
}

namespace {

void print_jobs(const netmc::v1::StatusReply& reply) {
  fmt::print("{:>6}  {:<10} {:>10}  {:<24} {}\n", "job", "state", "iterations", "label", "note");
  for (const auto& job : reply.jobs()) {
    const std::string note = !job.waiting_for().empty() ? "waits for " + job.waiting_for() : job.error();
    fmt::print("{:>6}  {:<10} {:>10}  {:<24} {}\n", job.job_id(), job.state(),
               fmt::format("{}/{}", job.iterations_done(), job.iterations_total()), job.label().substr(0, 24), note);
  }
  if (reply.jobs_size() == 0) fmt::print("(no job)\n");
}

}  // namespace

std::function<int()> add_status_command(CLI::App& app) {
  struct Flags {
    std::string server = "127.0.0.1:7300";
    std::uint64_t job = 0;
    bool json = false;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* status = app.add_subcommand("status", "The jobs a netmc-server holds: queued, running and the last 256 ended");
  status->add_option("JOB", flags->job, "Only this job (its id, as `netmc run` prints it)")->check(CLI::PositiveNumber);
  add_server_option(status, flags->server);
  status->add_flag("--json", flags->json, "Print the reply as JSON (netmc.v1.StatusReply), for scripts");
  return [flags]() -> int {
    const auto response = ask_server(
        flags->server, [&](netmc::v1::Request& request) { request.mutable_status()->set_job_id(flags->job); });
    if (flags->job != 0 && response.status().jobs_size() == 0) {
      throw std::runtime_error("server " + flags->server + ": no job " + std::to_string(flags->job) +
                               " (never submitted, or ended more than 256 jobs ago)");
    }
    if (flags->json) {
      fmt::print("{}\n", job::to_json(response.status()));
    } else {
      print_jobs(response.status());
    }
    return 0;
  };
}

std::function<int()> add_cancel_command(CLI::App& app) {
  struct Flags {
    std::string server = "127.0.0.1:7300";
    std::uint64_t job = 0;
    std::string job_token_file;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cancel = app.add_subcommand(
      "cancel", "Cancel a job of another connection: with its job token (saved by netmc submit, found here for the "
                "same --server and job) or the server's admin token (NETMC_TOKEN_FILE naming the file of netmc-server "
                "--admin-token-file); Ctrl-C on `netmc run` cancels its own job");
  cancel->add_option("JOB", flags->job, "The job's id")->required()->check(CLI::PositiveNumber);
  add_server_option(cancel, flags->server);
  cancel->add_option("--job-token-file", flags->job_token_file,
                     "The job's token file (default: the one netmc submit saved in $XDG_STATE_HOME/netmc/jobs, or "
                     "~/.local/state/netmc/jobs)");
  return [flags]() -> int {
    const std::optional<std::string> token =
        flags->job_token_file.empty()
            ? saved_job_token(flags->server, flags->job)
            : std::optional(management::AccessToken::from_file(flags->job_token_file).value());
    print_jobs(ask_server(flags->server, [&](netmc::v1::Request& request) {
                 request.mutable_cancel()->set_job_id(flags->job);
                 if (token) request.mutable_cancel()->set_cancel_token(*token);
               }).status());
    // Cancelled (a refusal throws above): the saved token has done its work.
    if (flags->job_token_file.empty()) forget_job_token(flags->server, flags->job);
    return 0;
  };
}

namespace {

// "90s", "30m", "24h", "7d": seconds.
double parse_age_s(const std::string& text) {
  static const std::map<char, double> units{{'s', 1.0}, {'m', 60.0}, {'h', 3600.0}, {'d', 86400.0}};
  const auto unit = text.empty() ? units.end() : units.find(text.back());
  double value = 0.0;
  std::size_t used = 0;
  try {
    if (unit != units.end()) value = std::stod(text.substr(0, text.size() - 1), &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (unit == units.end() || used + 1 != text.size() || !std::isfinite(value) || value <= 0.0 || value > 1e6) {
    throw std::invalid_argument("--since: expected an age such as 90s, 30m, 24h or 7d (up to 1e6 of the unit), got '" +
                                text.substr(0, 40) + "'");
  }
  return value * unit->second;
}

std::string format_unix_time(double unix_s) {
  if (unix_s <= 0.0) return "-";
  const auto time = static_cast<std::time_t>(unix_s);
  std::tm local{};
  localtime_r(&time, &local);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S", &local);
  return text;
}

}  // namespace

std::function<int()> add_jobs_command(CLI::App& app) {
  struct Flags {
    std::string server = "127.0.0.1:7300";
    std::string state_dir;
    std::string state;
    std::string label;
    std::string since;
    std::uint32_t limit = 50;
    bool json = false;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* jobs = app.add_subcommand(
      "jobs", "The server's job history, newest first: every job its job store keeps (netmc-server --state-dir; "
              "without one, the jobs in its memory), with who submitted it, when, and how it ended");
  add_server_option(jobs, flags->server);
  jobs->add_option("--state-dir", flags->state_dir,
                   "Read the job store in this directory (netmc-server's --state-dir) instead of asking a server "
                   "(--server is then not used): works with the server down; read-only, beside a running server too");
  jobs->add_option("--state", flags->state, "Only jobs in this state")
      ->check(CLI::IsMember({"queued", "running", "done", "failed", "cancelled"}));
  jobs->add_option("--label", flags->label, "Only jobs whose label contains this text");
  jobs->add_option("--since", flags->since, "Only jobs accepted within this age: 90s, 30m, 24h, 7d");
  jobs->add_option("--limit", flags->limit, "At most this many jobs")->check(CLI::Range(1, 10000));
  jobs->add_flag("--json", flags->json, "Print the reply as JSON (netmc.v1.JobList), for scripts");
  return [flags]() -> int {
    const double since_unix_s =
        flags->since.empty()
            ? 0.0
            : std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count() -
                  parse_age_s(flags->since);
    netmc::v1::ListJobs asked;
    asked.set_state(flags->state);
    asked.set_label_contains(flags->label);
    asked.set_since_unix_s(since_unix_s);
    asked.set_limit(flags->limit);
    netmc::v1::Response response;
    if (flags->state_dir.empty()) {
      response = ask_server(flags->server, [&](netmc::v1::Request& request) { *request.mutable_jobs() = asked; });
    } else {
      *response.mutable_jobs() = store::job_list(store::JobStore::read(flags->state_dir, store::job_filter(asked)), true);
    }
    const auto& list = response.jobs();
    if (flags->json) {
      fmt::print("{}\n", job::to_json(list));
      return 0;
    }
    fmt::print("{:>6}  {:<10} {:>10}  {:<19}  {:<19}  {:<22} {:<24} {}\n", "job", "state", "iterations", "accepted",
               "ended", "owner", "label", "note");
    for (const auto& job : list.jobs()) {
      fmt::print("{:>6}  {:<10} {:>10}  {:<19}  {:<19}  {:<22} {:<24} {}\n", job.job_id(), job.state(),
                 fmt::format("{}/{}", job.iterations_done(), job.iterations_total()),
                 format_unix_time(job.accepted_unix_s()), format_unix_time(job.ended_unix_s()),
                 job.owner().substr(0, 22), job.label().substr(0, 24), job.error());
    }
    if (list.jobs_size() == 0) fmt::print("(no job)\n");
    if (!list.persistent()) fmt::print("(from the server's memory: it was started without --state-dir)\n");
    if (!flags->state_dir.empty()) fmt::print("(read from {} without a server)\n", flags->state_dir);
    return 0;
  };
}

}  // namespace netmc::cli
